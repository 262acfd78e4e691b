// Every command's help names its page of the manual, and that page exists.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "support/run_command.hpp"

namespace tumble::app {
namespace {

using ::testing::HasSubstr;
using tumble::testing::run_command;
using tumble::testing::tumble_executable;

TEST(ManualPages, EveryCommandsHelpNamesItsExistingPage) {
  for (const std::string command : {"inspect", "simulate", "render", "compare", "bench",
                                    "stability", "view", "inertials", "merge", "farm"}) {
    const auto help = run_command(tumble_executable() + " " + command + " --help");
    EXPECT_EQ(help.status, 0) << command << ": " << help.err;
    const std::string page = "docs/" + command + ".md";
    EXPECT_THAT(help.out, HasSubstr("Manual: " + page)) << command;
    EXPECT_TRUE(std::filesystem::is_regular_file(std::filesystem::path(TUMBLE_SOURCE_DIR) / page))
        << page;
  }
}

TEST(ManualPages, TopLevelHelpPointsFarmAtItsPage) {
  const auto help = run_command(tumble_executable() + " --help");
  EXPECT_EQ(help.status, 0) << help.err;
  EXPECT_THAT(help.out, HasSubstr("(docs/farm.md)"));
  EXPECT_THAT(help.out, ::testing::Not(HasSubstr("README")));
}

}  // namespace
}  // namespace tumble::app
