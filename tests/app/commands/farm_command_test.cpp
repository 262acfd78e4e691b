// `tumble farm` end to end without running a job: the script it prints for a command, and its
// one-line errors for bad options and commands.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "support/command_test.hpp"

namespace tumble::testing {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

class FarmCommand : public CommandTest {
 protected:
  void SetUp() override {
    CommandTest::SetUp();
    scene_ = write_scene(fast_needle_scene(), "needle scene.json");
  }
  /// `tumble farm ARGS` run in the test's folder.
  CommandResult farm(const std::string& args) const {
    return run_command("cd '" + dir_.string() + "' && " + tumble_executable() + " farm " + args);
  }
  std::string scene_;
};

TEST_F(FarmCommand, PrintsTheSlurmSubmitScript) {
  const auto result = farm(
      "slurm --shards 3 --partition short --time 20 --assume-shared -- tumble bench "
      "'needle scene.json' --duration 1 -o res");
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_EQ(result.err, "");
  EXPECT_THAT(result.out, StartsWith("#!/bin/bash\n"));
  EXPECT_THAT(result.out, HasSubstr("#SBATCH --array=0-2\n"));
  EXPECT_THAT(result.out, HasSubstr("#SBATCH --partition=short\n#SBATCH --time=20\n"));
  EXPECT_THAT(result.out, HasSubstr("exec " + tumble_executable() + " bench '" + scene_ +
                                    "' --duration 1 --shard \"$SLURM_ARRAY_TASK_ID\"/3 -o " +
                                    dir_.string() + "/res.parts/part-\"$SLURM_ARRAY_TASK_ID\"\n"));
  EXPECT_THAT(result.out, HasSubstr("exec " + tumble_executable() + " merge " + dir_.string() +
                                    "/res.parts/part-{0..2} -o " + dir_.string() + "/res\n"));
  EXPECT_THAT(result.out, HasSubstr("--dependency=afterok:\"$shards\""));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "res.parts")) << "printing made the parts folder";
}

TEST_F(FarmCommand, PrintsTheParallelLine) {
  const auto result =
      farm("parallel --shards 2 --jobs 2 -- tumble render 'needle scene.json' -o v.mp4");
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_THAT(result.out,
              HasSubstr(" && parallel -q --halt now,fail=1 --jobs 2 " + tumble_executable() +
                        " render '" + scene_ + "' --shard '{}/2'"));
  EXPECT_THAT(result.out, HasSubstr("::: {0..1} && " + tumble_executable() + " merge "));
}

TEST_F(FarmCommand, LocalPathsAreAnErrorForWorkersElsewhere) {
  const auto result = farm("slurm --shards 2 -- tumble bench 'needle scene.json' -o res");
  const auto kind = run_command("stat -f -c %T '" + dir_.string() + "'");
  if (kind.out.find("nfs") != std::string::npos) GTEST_SKIP() << "the test folder is shared";
  EXPECT_EQ(result.status, 1);
  EXPECT_EQ(result.out, "");
  EXPECT_THAT(result.err,
              HasSubstr("tumble farm slurm: warning: '" + scene_ + "' is on a local filesystem ("));
  EXPECT_THAT(result.err, HasSubstr("workers on other machines will not see it\n"));
  EXPECT_THAT(result.err, HasSubstr("\ntumble farm slurm: error: the paths above on local "
                                    "filesystems must be on one the workers share"));
  // Local slots of GNU parallel see this machine's files: no check.
  EXPECT_EQ(farm("parallel --shards 2 -- tumble bench 'needle scene.json' -o res").status, 0);
}

TEST_F(FarmCommand, BadOptionsAndCommandsAreOneLineErrors) {
  const std::string bench = " -- tumble bench 'needle scene.json' -o res";
  const std::pair<std::string, std::string> cases[] = {
      {"slurm --assume-shared" + bench, "tumble farm slurm: error: --shards N is required\n"},
      {"slurm --shards 2 --assume-shared --time 1h" + bench,
       "tumble farm slurm: error: --time: expected minutes, MM:SS, HH:MM:SS, D-HH, D-HH:MM or "
       "D-HH:MM:SS, got '1h'\n"},
      {"slurm --shards 2 --assume-shared --wait" + bench,
       "tumble farm slurm: error: --wait needs --submit\n"},
      {"slurm --shards 2 --assume-shared -- tumble bench 'needle scene.json' --shard 0/2 -o res",
       "tumble farm slurm: error: tumble bench: already has --shard; give the whole command: "
       "tumble farm adds --shard I/N to each part\n"},
      {"slurm --shards 2 --assume-shared -- tumble simulate 'needle scene.json'",
       "tumble farm slurm: error: 'tumble simulate' cannot be farmed: expected render, compare, "
       "bench, stability or inspect\n"},
      {"slurm --shards 2 --assume-shared -- tumble bench nothing.json -o res",
       "tumble farm slurm: error: input '" + dir_.string() +
           "/nothing.json': no such file or folder\n"},
      {"slurm --shards 2 --assume-shared",
       "tumble farm slurm: error: no tumble command: give it "
       "after '--', e.g. -- tumble render SCENE -o OUT.mp4\n"},
      {"parallel -S a,b" + bench,
       "tumble farm parallel: error: --shards N is required with -S hosts\n"},
      {"parallel --shards 2 --tumble /no/tumble" + bench,
       "tumble farm parallel: error: tumble executable '/no/tumble': not an executable file\n"},
  };
  for (const auto& [args, message] : cases) {
    const auto result = farm(args);
    EXPECT_EQ(result.status, 1) << args;
    EXPECT_EQ(result.err, message) << args;
    EXPECT_EQ(result.out, "") << args;
  }
  const auto zero = farm("slurm --shards 0" + bench);
  EXPECT_EQ(zero.status, 1);
  EXPECT_THAT(zero.err,
              StartsWith("tumble farm: error: --shards: Value 0 not in range 1 to 100000"));
}

}  // namespace
}  // namespace tumble::testing
