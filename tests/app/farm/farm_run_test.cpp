// tumble farm's job in process (app/farm/farm_run.hpp): the shard count it decides, the meshes
// the caller reads from each scene reaching the path checks, and its one-line errors.
#include "app/farm/farm_run.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "app/farm/farm_paths.hpp"
#include "support/command_test.hpp"
#include "support/input_error.hpp"

namespace tumble::app {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

class FarmRun : public testing::CommandTest {
 protected:
  void SetUp() override {
    CommandTest::SetUp();
    scene_ = write_scene(testing::fast_needle_scene());
    mesh_ = path("ball.obj");
    std::ofstream(mesh_) << "v 0 0 0\n";
    options_.engine = "parallel";
    options_.tumble = testing::tumble_executable();
    options_.command = {"tumble", "bench", scene_, "-o", path("res")};
  }
  /// run_farm_job with a reader that records the scenes it is asked about and names `meshes`.
  std::string run(const std::vector<std::string>& meshes, std::ostream& err) {
    std::ostringstream out;
    run_farm_job(
        options_,
        [&](const fs::path& scene) {
          asked_.push_back(scene.string());
          return std::vector<fs::path>(meshes.begin(), meshes.end());
        },
        out, err);
    return out.str();
  }
  std::string scene_;
  std::string mesh_;
  FarmOptions options_;
  std::vector<std::string> asked_;
};

TEST_F(FarmRun, PrintsTheParallelLineForTheShardsAskedAndReadsEachScenesMeshes) {
  options_.shards = 3;
  std::ostringstream err;
  const std::string out = run({mesh_}, err);
  EXPECT_THAT(out, HasSubstr(" bench " + scene_ + " --shard '{}/3'"));
  EXPECT_THAT(out, HasSubstr("::: {0..2} && " + options_.tumble + " merge "));
  EXPECT_THAT(asked_, ElementsAre(scene_));
  EXPECT_EQ(err.str(), "");
}

TEST_F(FarmRun, ParallelOnThisMachineAloneTakesItsJobSlotsAsTheShardCount) {
  options_.slots.jobs = 5;
  std::ostringstream err;
  EXPECT_THAT(run({mesh_}, err), HasSubstr("::: {0..4} && "));
}

TEST_F(FarmRun, AMeshTheSceneNamesMustExist) {
  options_.shards = 2;
  const std::string missing = path("missing.obj");
  std::ostringstream err;
  EXPECT_THAT(testing::input_error_of([&] {
                run({mesh_, missing}, err);
              }),
              HasSubstr("input '" + missing + "': no such file"));
}

TEST_F(FarmRun, MeshesOnALocalFilesystemAreAnErrorForWorkersElsewhere) {
  if (filesystem_of(dir_).sharing != Sharing::kLocal) GTEST_SKIP() << "the test folder is shared";
  options_.shards = 2;
  options_.slots.hosts = {"worker1"};
  std::ostringstream err;
  EXPECT_THAT(testing::input_error_of([&] { run({mesh_}, err); }),
              HasSubstr("the paths above on local filesystems must be on one the workers share"));
  EXPECT_THAT(err.str(), HasSubstr("tumble farm parallel: warning: '" + mesh_ +
                                   "' is on a local filesystem ("));
  options_.assume_shared = true;  // then every path is taken as the workers see it
  std::ostringstream quiet;
  EXPECT_THAT(run({mesh_}, quiet), HasSubstr("::: {0..1} && "));
  EXPECT_EQ(quiet.str(), "");
}

TEST_F(FarmRun, ErrorsNameWhatIsMissing) {
  std::ostringstream err;
  options_.slots.hosts = {"worker1"};
  EXPECT_EQ(testing::input_error_of([&] { run({}, err); }), "--shards N is required with -S hosts");
  options_.engine = "slurm";
  EXPECT_EQ(testing::input_error_of([&] { run({}, err); }), "--shards N is required");
  options_.command.clear();
  EXPECT_THAT(testing::input_error_of([&] { run({}, err); }),
              HasSubstr("no tumble command: give it after '--'"));
}

}  // namespace
}  // namespace tumble::app
