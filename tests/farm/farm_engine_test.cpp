// tumble farm on real engines: a one-node Slurm cluster started here (slurm_cluster.hpp) and
// GNU parallel on local slots. Each farmed job's merged output is held to the same command run
// on one machine. Skipped, with the reason, where Slurm cannot start or parallel is missing.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "farm/farm_outputs.hpp"
#include "farm/slurm_cluster.hpp"

namespace tumble::testing {
namespace {

// Skips the test (GTEST_SKIP returns from the test itself) when this build cannot shard.
#define SKIP_WITHOUT_SHARDING()                                                         \
  do {                                                                                  \
    const std::string missing = sharding_missing();                                     \
    if (!missing.empty()) GTEST_SKIP() << missing << " (issue 16's --shard and merge)"; \
  } while (false)

using ::testing::HasSubstr;

/// A test's own folder, and the runs of tumble in it.
class FarmEngine : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fresh_directory(::testing::UnitTest::GetInstance()->current_test_info()->name());
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  CommandResult tumble(const std::string& args) const {
    return run_command("cd '" + dir_.string() + "' && " + tumble_executable() + " " + args);
  }
  /// The local, unsharded run of `command` (tumble COMMAND ... -o OUT).
  void run_locally(const std::string& command) const {
    const CommandResult local = tumble(command);
    ASSERT_EQ(local.status, 0) << local.err;
  }

  std::filesystem::path dir_;
};

class FarmSlurm : public FarmEngine {
 protected:
  static void SetUpTestSuite() { cluster_ = std::make_unique<SlurmCluster>(); }
  static void TearDownTestSuite() { cluster_.reset(); }
  void SetUp() override {
    if (!cluster_->skip_reason().empty()) GTEST_SKIP() << cluster_->skip_reason();
    FarmEngine::SetUp();
  }
  /// tumble farm slurm with the job submitted and waited for.
  CommandResult farm(const std::string& args) const {
    return tumble("farm slurm --assume-shared --submit --wait " + args);
  }

  static std::unique_ptr<SlurmCluster> cluster_;
};

std::unique_ptr<SlurmCluster> FarmSlurm::cluster_;

// The cluster itself, with a command every tumble has: an array job whose two tasks render
// frame ranges (--frames) give the frames of one local render, byte for byte.
TEST_F(FarmSlurm, ClusterRunsAnArrayJobOfFrameRanges) {
  run_locally("render " + demo_scene() + " " + kDemoRenderOptions + " -o local/");
  std::ofstream(dir_ / "frames.sbatch")
      << "#!/bin/bash\n#SBATCH --array=0-1\nstart=$((SLURM_ARRAY_TASK_ID * 40))\n"
      << "exec " << tumble_executable() << " render " << demo_scene() << " " << kDemoRenderOptions
      << " --frames $start:$((start + 40)) -o " << path("farmed-") << "$SLURM_ARRAY_TASK_ID/\n";
  const CommandResult submitted =
      run_command("cd '" + dir_.string() + "' && sbatch --wait -o slurm-%A_%a.out frames.sbatch");
  ASSERT_EQ(submitted.status, 0) << submitted.err << submitted.out;
  const auto local = directory_entries(dir_ / "local");
  ASSERT_EQ(local.size(), 81u);
  std::size_t frames = 0;
  for (const char* task : {"farmed-0", "farmed-1"}) {
    const auto farmed = directory_entries(dir_ / task);
    EXPECT_EQ(farmed.size(), 40u) << task;
    for (const std::string& frame : farmed) {
      ++frames;
      EXPECT_EQ(read_text(dir_ / task / frame), read_text(dir_ / "local" / frame)) << frame;
    }
  }
  EXPECT_EQ(frames, 80u) << "frames 0 to 79";
  EXPECT_EQ(directory_entries(dir_ / "farmed-1").front(), "frame_000040.png");
}

TEST_F(FarmSlurm, ShardedRenderEqualsTheLocalRender) {
  SKIP_WITHOUT_SHARDING();
  const std::string render = "render " + demo_scene() + " " + kDemoRenderOptions;
  run_locally(render + " -o local.mp4");
  const CommandResult farmed = farm("--shards 2 -- tumble " + render + " -o 'farmed demo.mp4'");
  ASSERT_EQ(farmed.status, 0) << farmed.err;
  EXPECT_THAT(farmed.out, ::testing::MatchesRegex("shards: Slurm job [0-9]+; merge: Slurm job "
                                                  "[0-9]+\nmerged: .*farmed demo.mp4\n"));
  EXPECT_TRUE(std::filesystem::exists(path("farmed demo.mp4.parts/part-1.mp4")));
  expect_same_video(path("farmed demo.mp4"), path("local.mp4"));
}

TEST_F(FarmSlurm, ShardedBenchEqualsTheLocalBench) {
  SKIP_WITHOUT_SHARDING();
  const std::string bench = "bench " + demo_scene() + " " + kDemoBenchOptions;
  run_locally(bench + " -o local");
  const CommandResult farmed = farm("--shards 2 -- tumble " + bench + " -o farmed");
  ASSERT_EQ(farmed.status, 0) << farmed.err;
  expect_same_bench(dir_ / "farmed", dir_ / "local");
}

// A shard that fails fails the job: the merge job, which would wait for ever, is cancelled, and
// the message names the failed task's log and its last line.
TEST_F(FarmSlurm, AFailedShardFailsTheJobAndCancelsTheMerge) {
  const CommandResult farmed =
      farm("--shards 2 -- tumble bench " + demo_scene() + " --integrators nonsense -o out");
  EXPECT_EQ(farmed.status, 1);
  EXPECT_THAT(farmed.err, ::testing::MatchesRegex(
                              "tumble farm slurm: error: Slurm job [0-9]+: shard task 0 FAILED, 1 "
                              "FAILED; merge job [0-9]+ cancelled; see '.*/out.parts/"
                              "slurm-[0-9]+_0.out': tumble bench: error: .*\n"));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "out"));
  EXPECT_EQ(run_command("squeue -h").out, "") << "a job left in the queue";
}

class FarmParallel : public FarmEngine {
 protected:
  void SetUp() override {
    if (run_command("command -v parallel").status != 0) {
      GTEST_SKIP() << "GNU parallel is not installed (apt-get install parallel)";
    }
    FarmEngine::SetUp();
  }
  CommandResult farm(const std::string& args) const {
    return tumble("farm parallel --run --jobs 2 " + args);
  }
};

TEST_F(FarmParallel, ShardedRenderEqualsTheLocalRender) {
  SKIP_WITHOUT_SHARDING();
  const std::string render = "render " + demo_scene() + " " + kDemoRenderOptions;
  run_locally(render + " -o local.mp4");
  const CommandResult farmed = farm("--shards 3 -- tumble " + render + " -o \"it's.mp4\"");
  ASSERT_EQ(farmed.status, 0) << farmed.err;
  expect_same_video(path("it's.mp4"), path("local.mp4"));
}

TEST_F(FarmParallel, ShardedBenchEqualsTheLocalBench) {
  SKIP_WITHOUT_SHARDING();
  const std::string bench = "bench " + demo_scene() + " " + kDemoBenchOptions;
  run_locally(bench + " -o local");
  const CommandResult farmed = farm("--shards 2 -- tumble " + bench + " -o 'farmed bench'");
  ASSERT_EQ(farmed.status, 0) << farmed.err;
  expect_same_bench(dir_ / "farmed bench", dir_ / "local");
}

TEST_F(FarmParallel, AFailedShardStopsBeforeTheMerge) {
  const CommandResult farmed =
      farm("--shards 2 -- tumble bench " + demo_scene() + " --integrators nonsense -o out");
  EXPECT_EQ(farmed.status, 1);
  EXPECT_THAT(farmed.err, HasSubstr("tumble farm parallel: error: the shards or the merge failed"));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "out"));
}

}  // namespace
}  // namespace tumble::testing
