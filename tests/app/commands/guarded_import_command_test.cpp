// `tumble inspect` on files that crash assimp 5.2 itself (found by fuzzing; the import runs
// assimp in a child process, engine/src/isolated_import.hpp): a refusal in one line and exit
// status 1, where the process used to die by SIGSEGV. The file's bytes are the fuzz input's
// after its first byte, which chose the extension.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>

#include "support/run_command.hpp"

namespace tumble::app {
namespace {

using ::testing::HasSubstr;
using tumble::testing::fresh_directory;
using tumble::testing::run_command;
using tumble::testing::tumble_executable;

TEST(GuardedImport, AnOffThatCrashesAssimpIsRefusedInOneLine) {
  std::ifstream in(
      std::string(TUMBLE_SOURCE_DIR) + "/tests/fuzz/corpus/mesh_import/regression_assimp_off_segv",
      std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_FALSE(bytes.empty());
  const auto file = fresh_directory("guarded") / "crash.off";
  std::ofstream(file, std::ios::binary) << bytes.substr(1);
  const auto result = run_command(tumble_executable() + " inspect " + file.string());
  EXPECT_EQ(result.status, 1) << result.err;
  EXPECT_EQ(result.out, "");
  EXPECT_EQ(result.err, "tumble inspect: error: " + file.string() +
                            ": assimp crashed reading it (SIGSEGV, Segmentation fault): the file "
                            "is malformed in a way assimp does not survive\n");
}

}  // namespace
}  // namespace tumble::app
