// What tumble farm checks of a job's paths: they exist, and which filesystem each is on (the
// names coreutils' `stat -f` gives are the oracle), and the sbatch and scontrol text it reads.
#include "app/farm/farm_paths.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <fstream>
#include <string>

#include "app/farm/farm_slurm_run.hpp"
#include "support/input_error.hpp"
#include "support/run_command.hpp"

namespace tumble::app {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

TEST(FarmPaths, NamesTheFilesystemsByTheirMagicNumbers) {
  EXPECT_EQ(filesystem_kind(0x6969).name, "nfs");
  EXPECT_EQ(filesystem_kind(0x6969).sharing, Sharing::kNetwork);
  EXPECT_EQ(filesystem_kind(0x0BD00BD0).name, "lustre");
  EXPECT_EQ(filesystem_kind(0x47504653).name, "gpfs");
  EXPECT_EQ(filesystem_kind(0x19830326).name, "beegfs");
  EXPECT_EQ(filesystem_kind(0x00C36400).name, "ceph");
  // CIFS's magic is above 2^31: a sign-extended f_type is the same filesystem.
  EXPECT_EQ(filesystem_kind(static_cast<std::int32_t>(0xFF534D42)).name, "cifs");
  EXPECT_EQ(filesystem_kind(0xFF534D42).sharing, Sharing::kNetwork);
  EXPECT_EQ(filesystem_kind(0x01021994).name, "tmpfs");
  EXPECT_EQ(filesystem_kind(0x01021994).sharing, Sharing::kLocal);
  EXPECT_EQ(filesystem_kind(0xEF53).sharing, Sharing::kLocal);
  EXPECT_EQ(filesystem_kind(0x65735546).sharing, Sharing::kUnknown);
  EXPECT_EQ(filesystem_kind(0x12345678).name, "0x12345678");
  EXPECT_EQ(filesystem_kind(0x12345678).sharing, Sharing::kUnknown);
}

TEST(FarmPaths, AgreesWithStatOnThisMachinesFilesystems) {
  const std::string temp = fs::temp_directory_path().string();
  for (const std::string& path :
       {std::string("/"), std::string("/dev/shm"), std::string("/proc"), temp}) {
    const auto stat = tumble::testing::run_command("stat -f -c %t '" + path + "'");
    ASSERT_EQ(stat.status, 0) << stat.err;
    const auto magic = static_cast<std::int64_t>(std::stoull(stat.out, nullptr, 16));
    EXPECT_EQ(filesystem_of(path).name, filesystem_kind(magic).name) << path;
  }
  const auto shm = tumble::testing::run_command("stat -f -c %T /dev/shm");
  if (shm.out == "tmpfs\n") {
    EXPECT_EQ(filesystem_of("/dev/shm").sharing, Sharing::kLocal);
    // A path not made yet is on its nearest existing folder's filesystem.
    EXPECT_EQ(filesystem_of("/dev/shm/not/yet/there.mp4").name, "tmpfs");
  }
}

class FarmPathChecks : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = tumble::testing::fresh_directory("farm_paths");
    std::ofstream(dir_ / "scene.json") << "{}";
    std::ofstream(dir_ / "tumble") << "#!/bin/sh\n";
    fs::permissions(dir_ / "tumble", fs::perms::owner_all);
    std::ofstream(dir_ / "tumble-draw") << "#!/bin/sh\n";
    fs::permissions(dir_ / "tumble-draw", fs::perms::owner_all);
  }
  void TearDown() override { fs::remove_all(dir_); }

  FarmJob job(const std::string& output) const {
    return parse_farm_job({"render", "scene.json", "-o", output}, dir_);
  }
  std::string error_of(const JobPaths& paths) const {
    return tumble::testing::input_error_of([&] { check_job_paths(paths); });
  }
  fs::path dir_;
};

TEST_F(FarmPathChecks, EveryPathMustBeThere) {
  const JobPaths good = job_paths(job("out.mp4"), dir_ / "tumble", {});
  EXPECT_EQ(good.output_folder, dir_);
  EXPECT_EQ(good.executables, (std::vector<fs::path>{dir_ / "tumble", dir_ / "tumble-draw"}));
  EXPECT_NO_THROW(check_job_paths(good));
  const JobPaths mesh = job_paths(job("out.mp4"), dir_ / "tumble", {dir_ / "t.obj"});
  EXPECT_EQ(error_of(mesh), "input '" + (dir_ / "t.obj").string() + "': no such file or folder");
  const JobPaths folder = job_paths(job("no/out.mp4"), dir_ / "tumble", {});
  EXPECT_EQ(error_of(folder), "output folder '" + (dir_ / "no").string() + "': no such folder");
  fs::permissions(dir_ / "tumble-draw", fs::perms::owner_read);
  EXPECT_THAT(error_of(good), HasSubstr("tumble-draw': not an executable file (it is built "
                                        "beside tumble)"));
  const JobPaths missing = job_paths(job("out.mp4"), dir_ / "none", {});
  EXPECT_THAT(error_of(missing), HasSubstr("/none': not an executable file"));
}

TEST_F(FarmPathChecks, SaysWhichPathsWorkersElsewhereWillNotSee) {
  if (filesystem_of(dir_).sharing != Sharing::kLocal) GTEST_SKIP() << "temp folder not local";
  bool local = false;
  const auto notes = sharing_notes(job_paths(job("out.mp4"), dir_ / "tumble", {}), local);
  EXPECT_TRUE(local);
  const std::string kind = filesystem_of(dir_).name;
  ASSERT_EQ(notes.size(), 4u);
  EXPECT_EQ(notes[0], "'" + (dir_ / "scene.json").string() + "' is on a local filesystem (" + kind +
                          "); workers on other machines will not see it");
  EXPECT_EQ(notes[1], "'" + dir_.string() + "' is on a local filesystem (" + kind +
                          "); workers on other machines will not see it");
  EXPECT_THAT(notes[2], HasSubstr("must be installed at the same path on every worker"));
}

TEST(FarmSlurmText, ReadsJobIdsAndStates) {
  EXPECT_EQ(parsable_job_id("12\n"), "12");
  EXPECT_EQ(parsable_job_id("12;cluster\n"), "12");
  EXPECT_EQ(tumble::testing::input_error_of([] { parsable_job_id("Submitted batch job 5\n"); }),
            "sbatch --parsable printed 'Submitted batch job 5', not a job id");
  // `scontrol show job -o` of an array job, as Slurm 22.05 prints it (fields shortened).
  const std::string shown =
      "JobId=4 ArrayJobId=3 ArrayTaskId=1 JobName=t UserId=root(0) JobState=FAILED "
      "Reason=NonZeroExitCode ExitCode=1:0 WorkDir=/tmp/a b\n"
      "JobId=3 ArrayJobId=3 ArrayTaskId=0 JobName=t UserId=root(0) JobState=COMPLETED "
      "Reason=None ExitCode=0:0\n";
  EXPECT_EQ(job_states(shown), (std::vector<std::string>{"FAILED", "COMPLETED"}));
  EXPECT_EQ(array_task_ids(shown), (std::vector<std::string>{"1", "0"}));
  EXPECT_TRUE(final_job_state("COMPLETED"));
  EXPECT_TRUE(final_job_state("OUT_OF_MEMORY"));
  EXPECT_TRUE(final_job_state("CANCELLED"));
  EXPECT_FALSE(final_job_state("PENDING"));
  EXPECT_FALSE(final_job_state("COMPLETING"));
  EXPECT_FALSE(final_job_state(""));
}

}  // namespace
}  // namespace tumble::app
