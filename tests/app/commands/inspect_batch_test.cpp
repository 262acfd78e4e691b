// `tumble inspect` batches: directories, -r, @LIST files, --jobs, the summary line.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <unistd.h>

#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "support/box_files.hpp"
#include "support/inspect_run.hpp"
#include "support/run_command.hpp"

namespace tumble::app {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::Not;
using tumble::testing::BoxMesh;
using tumble::testing::run_inspect_args;

namespace fs = std::filesystem;

/// The "file" of each line of a jsonl output.
std::vector<std::string> files_of(const std::string& jsonl) {
  std::vector<std::string> files;
  std::istringstream lines(jsonl);
  for (std::string line; std::getline(lines, line);) {
    files.push_back(nlohmann::json::parse(line).at("file").get<std::string>());
  }
  return files;
}

class InspectBatch : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = tumble::testing::fresh_directory("inspect_batch");
    fs::create_directories(dir_ / "parts" / "sub");
    fs::create_directories(dir_ / "parts" / ".cache");
    // Mixed formats: tumble's own reader (binary STL) and assimp's in its child (the rest).
    tumble::testing::write_box_binary_stl(at("parts/b.stl"), BoxMesh({1, 2, 3}));
    tumble::testing::write_box_obj(at("parts/a.obj"), BoxMesh({1, 1, 1}));
    tumble::testing::write_box_ply(at("parts/C.PLY"), BoxMesh({2, 2, 2}));
    tumble::testing::write_box_ascii_stl(at("parts/sub/d.stl"), BoxMesh({0.5, 0.5, 0.5}));
    tumble::testing::write_box_binary_stl(at("parts/.cache/hidden.stl"), BoxMesh({1, 1, 1}));
    tumble::testing::write_box_binary_stl(at("parts/.hidden.stl"), BoxMesh({1, 1, 1}));
    std::ofstream(at("parts/notes.txt")) << "not a mesh\n";
    std::ofstream(at("parts/sub/material.mtl")) << "newmtl x\n";
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string at(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

TEST_F(InspectBatch, DirectoryTakesItsMeshFilesSorted) {
  const auto run = run_inspect_args({"--jsonl", at("parts")});
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_THAT(files_of(run.out),
              ElementsAre(at("parts/C.PLY"), at("parts/a.obj"), at("parts/b.stl")));
  EXPECT_EQ(run.err, "tumble inspect: inspected 3 files: 3 ok, 0 with warnings, 0 refused\n");
}

TEST_F(InspectBatch, RecursiveDescendsButNotIntoHiddenFolders) {
  for (const char* flag : {"-r", "--recursive"}) {
    const auto run = run_inspect_args({"--jsonl", flag, at("parts")});
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_THAT(files_of(run.out), ElementsAre(at("parts/C.PLY"), at("parts/a.obj"),
                                               at("parts/b.stl"), at("parts/sub/d.stl")));
  }
}

TEST_F(InspectBatch, UnreadableSubDirectoryIsLeftOut) {
  if (::geteuid() == 0) GTEST_SKIP() << "root reads every directory";
  fs::create_directories(dir_ / "parts" / "locked");
  tumble::testing::write_box_binary_stl(at("parts/locked/e.stl"), BoxMesh({1, 1, 1}));
  fs::permissions(dir_ / "parts" / "locked", fs::perms::none);
  const auto run = run_inspect_args({"--jsonl", "-r", at("parts")});
  fs::permissions(dir_ / "parts" / "locked", fs::perms::owner_all);
  EXPECT_EQ(run.status, 0) << run.err;
  EXPECT_EQ(files_of(run.out).size(), 4u) << run.out;
}

TEST_F(InspectBatch, ListFileWithCommentsAndRelativePaths) {
  fs::create_directories(dir_ / "lists");
  std::ofstream(at("lists/parts.txt")) << "# the parts\n\n  ../parts/b.stl  \r\n"
                                       << at("parts/a.obj") << "\n"
                                       << "   # indented comment\n../parts/sub\n";
  const auto run = run_inspect_args({"--jsonl", "@" + at("lists/parts.txt")});
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_THAT(files_of(run.out), ElementsAre(at("lists/../parts/b.stl"), at("parts/a.obj"),
                                             at("lists/../parts/sub/d.stl")));
}

TEST_F(InspectBatch, MissingEntriesAreOneLineEachAndTheRestIsInspected) {
  std::ofstream(at("list.txt")) << "parts/b.stl\nparts/gone.stl\n@nested.txt\n";
  fs::create_directories(dir_ / "empty");
  const auto run =
      run_inspect_args({at("list.txt"), "@" + at("list.txt"), "@" + at("nope.txt"), at("empty")});
  EXPECT_EQ(run.status, 1);
  // list.txt without '@' is a mesh file of an unknown format.
  EXPECT_THAT(run.err, HasSubstr("tumble inspect: error: " + at("list.txt") + ": "));
  EXPECT_THAT(run.err,
              HasSubstr("tumble inspect: error: " + at("parts/gone.stl") + ": no such file\n"));
  EXPECT_THAT(run.err,
              HasSubstr("tumble inspect: error: " + at("nested.txt") + ": no such list file\n"));
  EXPECT_THAT(run.err,
              HasSubstr("tumble inspect: error: " + at("nope.txt") + ": no such list file\n"));
  EXPECT_THAT(run.err, HasSubstr("tumble inspect: error: " + at("empty") +
                                 ": no mesh files in the directory"));
  EXPECT_THAT(run.err, HasSubstr("inspected 6 files: 1 ok, 0 with warnings, 5 refused\n"));
  EXPECT_THAT(run.out, HasSubstr(at("parts/b.stl")));
}

TEST_F(InspectBatch, AtSignAloneAndAFileNamedWithOne) {
  const auto alone = run_inspect_args({"@"});
  EXPECT_EQ(alone.status, 1);
  EXPECT_EQ(alone.err,
            "tumble inspect: error: @: expected the name of a list file after '@' (@LIST)\n");
  // A mesh whose name starts with '@' is reached through its folder.
  tumble::testing::write_box_binary_stl(at("@part.stl"), BoxMesh({1, 1, 1}));
  const auto file = run_inspect_args({"--jsonl", (dir_ / "." / "@part.stl").string()});
  EXPECT_EQ(file.status, 0) << file.err;
}

TEST_F(InspectBatch, ListNamingItselfEnds) {
  std::ofstream(at("loop.txt")) << "@loop.txt\n";
  const auto run = run_inspect_args({"@" + at("loop.txt")});
  EXPECT_EQ(run.status, 1);
  EXPECT_THAT(run.err, HasSubstr("lists nested more than 16 deep"));
}

TEST_F(InspectBatch, JobsGiveTheSameOutputInTheSameOrder) {
  // Many files of mixed formats, one broken in the middle, and one with a warning.
  for (int i = 0; i < 12; ++i) {
    const BoxMesh box({1.0 + 0.5 * i, 1, 1});
    const std::string name = at("many/p" + std::to_string(10 + i));
    fs::create_directories(dir_ / "many");
    if (i % 3 == 0) tumble::testing::write_box_obj(name + ".obj", box);
    if (i % 3 == 1) tumble::testing::write_box_binary_stl(name + ".stl", box);
    if (i % 3 == 2) tumble::testing::write_box_ply(name + ".ply", box);
  }
  std::ofstream(at("many/p15_broken.obj")) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  tumble::testing::write_box_binary_stl(at("many/p99_large.stl"), BoxMesh({500, 1, 1}));
  for (const char* format : {"text", "jsonl", "json", "urdf"}) {
    const auto one = run_inspect_args({"--format", format, "--jobs", "1", at("many")});
    const auto two = run_inspect_args({"--format", format, "--jobs", "2", at("many")});
    const auto cores = run_inspect_args({"--format", format, "--jobs", "0", at("many")});
    EXPECT_EQ(one.status, 1);
    EXPECT_EQ(two.status, 1);
    EXPECT_EQ(one.out, two.out) << format;
    EXPECT_EQ(one.err, two.err) << format;
    EXPECT_EQ(one.out, cores.out) << format;
    EXPECT_THAT(one.err, HasSubstr("inspected 14 files: 12 ok, 1 with warnings, 1 refused\n"));
    EXPECT_THAT(one.err, HasSubstr("p15_broken.obj: "));
  }
  const auto jsonl = run_inspect_args({"--jsonl", "--jobs", "2", at("many")});
  const auto files = files_of(jsonl.out);
  ASSERT_EQ(files.size(), 14u);
  EXPECT_EQ(files[6], at("many/p15_broken.obj"));  // after p15.ply
  EXPECT_TRUE(std::is_sorted(files.begin(), files.end()));
  // json prints nothing when one failed, as before.
  EXPECT_TRUE(run_inspect_args({"--json", "--jobs", "2", at("many")}).out.empty());
}

TEST_F(InspectBatch, JsonOfADirectoryIsAnArrayEvenOfOneFile) {
  const auto run = run_inspect_args({"--json", at("parts/sub")});
  ASSERT_EQ(run.status, 0) << run.err;
  const auto json = nlohmann::json::parse(run.out);
  ASSERT_TRUE(json.is_array());
  EXPECT_EQ(json.size(), 1u);
  EXPECT_TRUE(run.err.empty()) << run.err;  // one file: no summary
}

TEST_F(InspectBatch, ExecutableSummaryAndStatus) {
  const auto run =
      tumble::testing::run_command(tumble::testing::tumble_executable() + " inspect --jobs 2 -r " +
                                   at("parts") + " " + at("parts/none.obj"));
  EXPECT_EQ(run.status, 1);
  EXPECT_THAT(run.err, HasSubstr("inspected 5 files: 4 ok, 0 with warnings, 1 refused\n"));
  EXPECT_THAT(run.out, HasSubstr(at("parts/sub/d.stl")));
  EXPECT_THAT(run.out, Not(HasSubstr("hidden")));
}

}  // namespace
}  // namespace tumble::app
