// Output folders written whole or not at all: what may be replaced, and the final move.
#include "app/support/output_folder.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "base/temporary_path.hpp"
#include "support/input_error.hpp"
#include "support/run_command.hpp"

namespace tumble::app {
namespace {

namespace fs = std::filesystem;
using testing::directory_entries;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using testing::input_error_of;
using testing::read_text;

const OutputFolderKind kBench{"bench", "report.md", "# tumble bench", "results.csv"};

void write(const fs::path& file, const std::string& text) {
  std::ofstream(file) << text;
}

class OutputFolderTest : public ::testing::Test {
 protected:
  void SetUp() override { root_ = testing::fresh_directory("OutputFolderTest"); }
  void TearDown() override { fs::remove_all(root_); }
  fs::path root_;
};

TEST_F(OutputFolderTest, AnAbsentFolderIsWrittenAsAHiddenTemporaryThenMovedIntoPlace) {
  const fs::path dir = root_ / "out";
  const fs::path tmp = start_output_folder(dir, kBench);
  EXPECT_EQ(tmp, root_ / (".out.tmp-" + std::to_string(::getpid())));
  EXPECT_TRUE(fs::is_directory(tmp));
  EXPECT_TRUE(fs::is_empty(tmp));
  EXPECT_FALSE(fs::exists(dir));
  write(tmp / "results.csv", "a\n");
  finish_output_folder(tmp, dir);
  EXPECT_THAT(directory_entries(root_), ElementsAre("out"));
  EXPECT_EQ(read_text(dir / "results.csv"), "a\n");
}

TEST_F(OutputFolderTest, AStaleTemporaryFromThisProcessIsClearedFirst) {
  const fs::path dir = root_ / "out";
  fs::create_directory(tumble::temporary_sibling(dir));
  write(tumble::temporary_sibling(dir) / "stale.txt", "x");
  const fs::path tmp = start_output_folder(dir, kBench);
  EXPECT_TRUE(fs::is_empty(tmp));
}

TEST_F(OutputFolderTest, AnEmptyFolderMayBeReplaced) {
  const fs::path dir = root_ / "out";
  fs::create_directory(dir);
  const fs::path tmp = start_output_folder(dir, kBench);
  write(tmp / "results.csv", "new\n");
  finish_output_folder(tmp, dir);
  EXPECT_THAT(directory_entries(dir), ElementsAre("results.csv"));
  EXPECT_THAT(directory_entries(root_), ElementsAre("out"));
}

TEST_F(OutputFolderTest, AnEarlierOutputIsReplacedWhole) {
  const fs::path dir = root_ / "out";
  fs::create_directory(dir);
  write(dir / "report.md", "# tumble bench\nold\n");
  write(dir / "results.csv", "old\n");
  write(dir / "old_plot.png", "old");
  const fs::path tmp = start_output_folder(dir, kBench);
  EXPECT_EQ(read_text(dir / "results.csv"), "old\n");  // untouched until finished
  write(tmp / "report.md", "# tumble bench\nnew\n");
  write(tmp / "results.csv", "new\n");
  finish_output_folder(tmp, dir);
  EXPECT_THAT(directory_entries(dir), ElementsAre("report.md", "results.csv"));
  EXPECT_EQ(read_text(dir / "results.csv"), "new\n");
  EXPECT_THAT(directory_entries(root_), ElementsAre("out"));  // no .old left behind
}

TEST_F(OutputFolderTest, TheTitleOnlyHasToStartTheFirstLine) {
  const fs::path dir = root_ / "out";
  fs::create_directory(dir);
  write(dir / "report.md", "# tumble bench of 3 scenes\n");
  write(dir / "results.csv", "");
  EXPECT_NO_THROW(start_output_folder(dir, kBench));
}

TEST_F(OutputFolderTest, AFolderOfOtherFilesIsRefused) {
  const fs::path dir = root_ / "photos";
  fs::create_directory(dir);
  write(dir / "holiday.jpg", "x");
  EXPECT_EQ(input_error_of([&] { start_output_folder(dir, kBench); }),
            "-o: " + dir.string() + " exists and is neither empty nor a previous bench output");
  EXPECT_THAT(directory_entries(root_), ElementsAre("photos"));
  EXPECT_THAT(directory_entries(dir), ElementsAre("holiday.jpg"));
}

TEST_F(OutputFolderTest, AReportWithoutItsDataOrWithAnotherTitleIsRefused) {
  const fs::path no_data = root_ / "no_data";
  fs::create_directory(no_data);
  write(no_data / "report.md", "# tumble bench\n");
  EXPECT_THAT(input_error_of([&] { start_output_folder(no_data, kBench); }),
              HasSubstr("neither empty nor a previous bench output"));

  const fs::path other = root_ / "other";
  fs::create_directory(other);
  write(other / "report.md", "# tumble stability\n");
  write(other / "results.csv", "");
  EXPECT_THAT(input_error_of([&] { start_output_folder(other, kBench); }),
              HasSubstr("neither empty nor a previous bench output"));

  const fs::path indented = root_ / "indented";
  fs::create_directory(indented);
  write(indented / "report.md", "\n# tumble bench\n");
  write(indented / "results.csv", "");
  EXPECT_THAT(input_error_of([&] { start_output_folder(indented, kBench); }),
              HasSubstr("neither empty nor a previous bench output"));
}

TEST_F(OutputFolderTest, AFileInTheWayIsRefused) {
  const fs::path file = root_ / "out";
  write(file, "x");
  EXPECT_EQ(input_error_of([&] { start_output_folder(file, kBench); }),
            "-o: " + file.string() + " exists and is not a directory");
  EXPECT_EQ(read_text(file), "x");
}

TEST_F(OutputFolderTest, AMissingParentIsAnErrorNotATreeOfNewFolders) {
  const fs::path dir = root_ / "typo" / "out";
  const std::string message = input_error_of([&] { start_output_folder(dir, kBench); });
  EXPECT_THAT(message,
              HasSubstr("-o: cannot create " + dir.string() + " (written first as .out.tmp-"));
  EXPECT_FALSE(fs::exists(root_ / "typo"));
}

TEST_F(OutputFolderTest, FinishingWithoutTheTemporaryKeepsTheEarlierOutput) {
  const fs::path dir = root_ / "out";
  fs::create_directory(dir);
  write(dir / "results.csv", "old\n");
  const std::string message =
      input_error_of([&] { finish_output_folder(root_ / ".gone.tmp-1", dir); });
  EXPECT_THAT(message,
              HasSubstr("-o: " + dir.string() + ": cannot move the new output into place"));
  EXPECT_EQ(read_text(dir / "results.csv"), "old\n");
  EXPECT_THAT(directory_entries(root_), ElementsAre("out"));
}

TEST_F(OutputFolderTest, AnEarlierOutputHoldingAnInputOrAnyOtherFileIsRefused) {
  // Replacing it would have deleted the scene kept beside the report.
  const fs::path dir = root_ / "out";
  fs::create_directory(dir);
  write(dir / "report.md", "# tumble bench\n");
  write(dir / "results.csv", "a\n");
  write(dir / "scene.json", "{}");
  EXPECT_EQ(input_error_of([&] { start_output_folder(dir, kBench); }),
            "-o: " + dir.string() + " exists and is neither empty nor a previous bench output");
  EXPECT_EQ(directory_entries(root_), std::vector<std::string>{"out"});
  EXPECT_EQ(read_text(dir / "scene.json"), "{}");
}

TEST_F(OutputFolderTest, ALinkToAFolderIsWrittenThroughAndStays) {
  fs::create_directory(root_ / "real");
  write(root_ / "real" / "report.md", "# tumble bench\n");
  write(root_ / "real" / "results.csv", "old\n");
  fs::create_directory_symlink("real", root_ / "out");
  const fs::path tmp = start_output_folder(root_ / "out", kBench);
  EXPECT_EQ(tmp.parent_path(), fs::canonical(root_));
  write(tmp / "results.csv", "new\n");
  finish_output_folder(tmp, root_ / "out");
  EXPECT_TRUE(fs::is_symlink(root_ / "out"));
  EXPECT_EQ(read_text(root_ / "real" / "results.csv"), "new\n");
  EXPECT_EQ(directory_entries(root_), (std::vector<std::string>{"out", "real"}));
}

TEST_F(OutputFolderTest, ALinkToAFileOrNothingIsRefused) {
  write(root_ / "file", "x");
  fs::create_symlink("file", root_ / "out");
  EXPECT_EQ(input_error_of([&] { start_output_folder(root_ / "out", kBench); }),
            "-o: cannot write '" + (root_ / "out").string() +
                "': it is a symbolic link to a regular file, not a directory (it is never "
                "replaced)");
  fs::create_symlink("nothing", root_ / "dangling");
  EXPECT_EQ(
      input_error_of([&] { start_output_folder(root_ / "dangling", kBench); }),
      "-o: cannot write '" + (root_ / "dangling").string() + "': it is a symbolic link to nothing");
  EXPECT_EQ(directory_entries(root_), (std::vector<std::string>{"dangling", "file", "out"}));
}

TEST_F(OutputFolderTest, AStaleTemporaryOfADeadProcessIsRemovedAndALiveOnesKept) {
  const auto dead = testing::run_command("sh -c 'echo $$'");
  const std::string pid = dead.out.substr(0, dead.out.find('\n'));
  fs::create_directory(root_ / (".out.tmp-" + pid));
  const std::string live = ".out.tmp-" + std::to_string(::getppid());
  fs::create_directory(root_ / live);
  const fs::path tmp = start_output_folder(root_ / "out", kBench);
  finish_output_folder(tmp, root_ / "out");
  EXPECT_EQ(directory_entries(root_), (std::vector<std::string>{live, "out"}));
}

}  // namespace
}  // namespace tumble::app
