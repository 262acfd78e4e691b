// End-to-end tests of what the commands read and write (issue 12): only regular files are
// read, an output never replaces a device, a link or an input, and an interrupted or killed run
// leaves nothing under the output's name.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "app/support/exit_status.hpp"
#include "support/box_files.hpp"
#include "support/command_test.hpp"
#include "support/run_command.hpp"
#include "support/scene_builder.hpp"

namespace tumble::app {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;
using tumble::testing::directory_entries;
using tumble::testing::read_text;
using tumble::testing::run_command;
using tumble::testing::tumble_executable;

nlohmann::json spinning_scene(double duration, double dt) {
  return testing::SceneBuilder()
      .duration(duration)
      .dt(dt)
      .body(testing::BodyBuilder("brick").angular_velocity({0.01, 3.0, 0.01}, "body"))
      .json();
}

class SafeIo : public testing::CommandTest {
 protected:
  testing::CommandResult tumble(const std::string& arguments) const {
    return run_command(tumble_executable() + " " + arguments);
  }

  /// Runs `command` in the background, waits for a temporary `.NAME.tmp-*` to appear in the
  /// folder, then sends `signal` and waits for the command's exit. `env --default-signal`
  /// undoes the shell's ignoring of SIGINT in a background job.
  testing::CommandResult interrupt(const std::string& command, const std::string& name,
                                   const std::string& signal) const {
    return run_command(
        "(env --default-signal=INT " + command + " & pid=$!; for i in $(seq 400); do ls -a '" +
        dir_.string() + "' | grep -q '^\\." + name +
        "\\.tmp' && break; sleep 0.02; done; sleep 0.3; kill -" + signal + " $pid; wait $pid)");
  }
};

TEST_F(SafeIo, AFifoGivenAsTheSceneIsRefusedAtOnce) {
  ASSERT_EQ(::mkfifo(path("scene.json").c_str(), 0644), 0);
  // Before, the open blocked forever; `timeout` turns a hang into status 124.
  const auto result =
      run_command("timeout 10 " + tumble_executable() + " simulate " + path("scene.json"));
  EXPECT_EQ(result.status, kExitInputError);
  EXPECT_THAT(result.err, HasSubstr("tumble simulate: error: " + path("scene.json") +
                                    ": is a FIFO, not a regular file; expected a scene file"));
}

TEST_F(SafeIo, DevZeroAsTheSceneIsRefusedAtOnce) {
  const auto result = run_command("timeout 10 " + tumble_executable() + " simulate /dev/zero");
  EXPECT_EQ(result.status, kExitInputError);
  EXPECT_THAT(result.err, HasSubstr("/dev/zero: is a character device, not a regular file"));
}

TEST_F(SafeIo, ASymlinkLoopAsTheSceneIsReportedAsALoop) {
  fs::create_symlink(dir_ / "b.json", dir_ / "a.json");
  fs::create_symlink(dir_ / "a.json", dir_ / "b.json");
  const auto result = tumble("simulate " + path("a.json"));
  EXPECT_EQ(result.status, kExitInputError);
  EXPECT_THAT(
      result.err,
      HasSubstr(path("a.json") + ": cannot open the scene file (JSON): a loop of symbolic links"));
}

TEST_F(SafeIo, ADeviceGivenAsTheCsvIsNeverReplaced) {
  // A null device of our own (as root; /dev/full itself was replaced by a regular file).
  if (::geteuid() != 0) GTEST_SKIP() << "mknod needs root";
  const std::string scene = write_scene(spinning_scene(0.1, 0.01));
  ASSERT_EQ(::mknod(path("null").c_str(), S_IFCHR | 0666, makedev(1, 3)), 0);
  const auto result = tumble("simulate " + scene + " --csv " + path("null"));
  EXPECT_EQ(result.status, kExitInputError);
  EXPECT_THAT(result.err, HasSubstr("cannot write '" + path("null") +
                                    "': it is a character device, not a regular file (it is "
                                    "never replaced)"));
  struct stat status {};
  ASSERT_EQ(::lstat(path("null").c_str(), &status), 0);
  EXPECT_TRUE(S_ISCHR(status.st_mode));
  EXPECT_EQ(directory_entries(dir_), (std::vector<std::string>{"null", "scene.json"}));
}

TEST_F(SafeIo, ALinkToADeviceIsRefusedAndALinkToAFileIsWrittenThrough) {
  const std::string scene = write_scene(spinning_scene(0.1, 0.01));
  fs::create_symlink("/dev/null", dir_ / "to_null.csv");
  const auto refused = tumble("simulate " + scene + " --csv " + path("to_null.csv"));
  EXPECT_EQ(refused.status, kExitInputError);
  EXPECT_THAT(refused.err, HasSubstr("cannot write '" + path("to_null.csv") +
                                     "': it is a symbolic link to a character device"));
  EXPECT_TRUE(fs::is_symlink(dir_ / "to_null.csv"));

  fs::create_directory(dir_ / "data");
  std::ofstream(dir_ / "data" / "run.csv") << "old";
  fs::create_symlink("data/run.csv", dir_ / "run.csv");
  const auto written = tumble("simulate " + scene + " --csv " + path("run.csv"));
  ASSERT_EQ(written.status, 0) << written.err;
  EXPECT_TRUE(fs::is_symlink(dir_ / "run.csv"));
  EXPECT_THAT(read_text(dir_ / "data" / "run.csv"), ::testing::StartsWith("t,body,x,y,z"));
  EXPECT_EQ(directory_entries(dir_ / "data"), std::vector<std::string>{"run.csv"});
}

TEST_F(SafeIo, TheSceneOrItsMeshAsTheCsvIsRefused) {
  const std::string scene = write_scene(spinning_scene(0.1, 0.01));
  const std::string before = read_text(scene);
  const auto same = tumble("simulate " + scene + " --csv " + scene);
  EXPECT_EQ(same.status, kExitInputError);
  EXPECT_THAT(same.err, HasSubstr("cannot write '" + scene + "': it is the input '" + scene +
                                  "' (an input is never overwritten)"));
  EXPECT_EQ(read_text(scene), before);

  // The mesh, reached through a link.
  const fs::path mesh = fs::path(TUMBLE_SOURCE_DIR) / "assets/meshes/t_handle.obj";
  fs::copy_file(mesh, dir_ / "handle.obj");
  nlohmann::json with_mesh = spinning_scene(0.1, 0.01);
  with_mesh["bodies"][0].erase("inertia");
  with_mesh["bodies"][0].erase("mass");
  with_mesh["bodies"][0]["mesh"] = "handle.obj";
  with_mesh["bodies"][0]["density"] = 1000;
  const std::string mesh_scene = write_scene(with_mesh, "mesh.json");
  fs::create_symlink(dir_ / "handle.obj", dir_ / "out.csv");
  const auto through = tumble("simulate " + mesh_scene + " --csv " + path("out.csv"));
  EXPECT_EQ(through.status, kExitInputError);
  EXPECT_THAT(through.err, HasSubstr("cannot write '" + path("out.csv") + "': it is the input '"));
  EXPECT_EQ(read_text(dir_ / "handle.obj"), read_text(mesh));
}

TEST_F(SafeIo, AFullDiskIsExitOneAndNothingUnderTheFinalName) {
  // A file size limit stands in for a full disk: writes fail with EFBIG.
  const std::string scene = write_scene(spinning_scene(5.0, 0.001));
  const auto result = run_command("ulimit -f 16; trap '' XFSZ; " + tumble_executable() +
                                  " simulate " + scene + " --csv " + path("out.csv"));
  EXPECT_EQ(result.status, kExitInputError);
  EXPECT_THAT(result.err, HasSubstr("cannot write '" + path("out.csv") +
                                    "': write failed: File "
                                    "too large"));
  EXPECT_EQ(directory_entries(dir_), std::vector<std::string>{"scene.json"});
}

TEST_F(SafeIo, InterruptedSimulateLeavesNothingAndExitsWith130) {
  const std::string scene = write_scene(spinning_scene(1e4, 1e-4));
  for (const std::string signal : {"INT", "TERM"}) {
    const auto result = interrupt(
        tumble_executable() + " simulate " + scene + " --every 1000 --csv " + path("x.csv"),
        "x\\.csv", signal);
    EXPECT_EQ(result.status, kExitInterrupted) << result.err;
    EXPECT_EQ(result.err, "tumble simulate: interrupted by SIG" + signal +
                              "; nothing written to '" + path("x.csv") + "'\n");
    EXPECT_EQ(result.out, "");
    EXPECT_EQ(directory_entries(dir_), std::vector<std::string>{"scene.json"});
  }
}

TEST_F(SafeIo, InterruptedBenchLeavesNothingAndExitsWith130) {
  const std::string scene = write_scene(spinning_scene(200.0, 0.001));
  const auto result = interrupt(
      tumble_executable() + " bench " + scene + " --repeat 1 -o " + path("out"), "out", "INT");
  EXPECT_EQ(result.status, kExitInterrupted) << result.err;
  EXPECT_THAT(result.err, HasSubstr("tumble bench: interrupted by SIGINT; nothing written to '" +
                                    path("out") + "'\n"));
  EXPECT_EQ(directory_entries(dir_), std::vector<std::string>{"scene.json"});
}

TEST_F(SafeIo, InterruptedInspectLeavesNothingAndExitsWith130) {
  // A list naming one box 20,000 times: seconds of inspection, with -o's temporary opened
  // before the first file is read. Before, the signal killed the process and left it behind.
  testing::write_box_binary_stl(dir_ / "box.stl", testing::BoxMesh({1, 2, 3}));
  {
    std::ofstream list(dir_ / "boxes.txt");
    for (int i = 0; i < 20000; ++i) list << "box.stl\n";
  }
  for (const std::string signal : {"INT", "TERM"}) {
    const auto result = interrupt(
        tumble_executable() + " inspect --jsonl @" + path("boxes.txt") + " -o " + path("x.jsonl"),
        "x\\.jsonl", signal);
    EXPECT_EQ(result.status, kExitInterrupted) << result.err;
    EXPECT_EQ(result.err, "tumble inspect: interrupted by SIG" + signal + "; nothing written to '" +
                              path("x.jsonl") + "'\n");
    EXPECT_EQ(result.out, "");
    EXPECT_EQ(directory_entries(dir_), (std::vector<std::string>{"box.stl", "boxes.txt"}));
  }
}

TEST_F(SafeIo, BenchStopsWithinALongCase) {
  // The second case, rk4 at dt 1e-5 over 2000 s (2e8 steps, a minute or more per run), is
  // running when SIGTERM comes: the run must stop there, not at the end of the case. `timeout`
  // turns a run that does not stop into status 137 (SIGKILL) long before the case ends;
  // --foreground, or it would pass the signal on twice (to the child and to its group), and
  // the second would stop tumble at once.
  const std::string scene = write_scene(spinning_scene(2000.0, 0.5));
  const auto result =
      interrupt("timeout --foreground -s KILL 60 " + tumble_executable() + " bench " + scene +
                    " --integrators rk4 --dts 0.5,1e-5 --repeat 1 -o " + path("out"),
                "out", "TERM");
  EXPECT_EQ(result.status, kExitInterrupted) << result.err;
  EXPECT_THAT(result.err, HasSubstr("tumble bench: interrupted by SIGTERM; nothing written to '" +
                                    path("out") + "'\n"));
  EXPECT_THAT(result.err, Not(HasSubstr("[2/2]")));
  EXPECT_EQ(directory_entries(dir_), std::vector<std::string>{"scene.json"});
}

TEST_F(SafeIo, InterruptedStabilityLeavesNothingAndExitsWith130) {
  const std::string scene = write_scene(spinning_scene(1e4, 1e-3));
  const auto result =
      interrupt(tumble_executable() + " stability " + scene + " -o " + path("out"), "out", "TERM");
  EXPECT_EQ(result.status, kExitInterrupted) << result.err;
  EXPECT_THAT(result.err,
              HasSubstr("tumble stability: interrupted by SIGTERM; nothing written to '" +
                        path("out") + "'\n"));
  EXPECT_EQ(directory_entries(dir_), std::vector<std::string>{"scene.json"});
}

TEST_F(SafeIo, StabilityStopsWithinALongRun) {
  // One run of rk4 at dt 1e-5 over 2000 s (2e8 steps, minutes) is under way when SIGTERM
  // comes: it must stop there, not at its end. `timeout` (--foreground: the signal passed on
  // once) turns a run that does not stop into status 137 long before that end.
  const std::string scene = write_scene(spinning_scene(2000.0, 0.5));
  const auto result =
      interrupt("timeout --foreground -s KILL 60 " + tumble_executable() + " stability " + scene +
                    " --integrators rk4 --dts 1e-5 -o " + path("out"),
                "out", "TERM");
  EXPECT_EQ(result.status, kExitInterrupted) << result.err;
  EXPECT_THAT(result.err,
              HasSubstr("tumble stability: interrupted by SIGTERM; nothing written to '" +
                        path("out") + "'\n"));
  EXPECT_EQ(directory_entries(dir_), std::vector<std::string>{"scene.json"});
}

TEST_F(SafeIo, AStaleTemporaryOfADeadProcessIsRemovedByTheNextRun) {
  const std::string scene = write_scene(spinning_scene(0.1, 0.01));
  // A process that has exited: its PID names no live process (until reused, which is unlikely
  // within the test).
  const auto dead = run_command("sh -c 'echo $$'");
  const std::string pid = dead.out.substr(0, dead.out.find('\n'));
  std::ofstream(dir_ / (".x.csv.tmp-" + pid)) << "half a file";
  fs::create_directory(dir_ / (".out.tmp-" + pid));
  // A live process's temporary (this test's) is left alone.
  const std::string live = ".x.csv.tmp-" + std::to_string(::getppid());
  std::ofstream(dir_ / live) << "in use";
  const auto result = tumble("simulate " + scene + " --csv " + path("x.csv"));
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_EQ(directory_entries(dir_),
            (std::vector<std::string>{".out.tmp-" + pid, live, "scene.json", "x.csv"}));
}

TEST_F(SafeIo, ARunOfTooManyStepsOrTooLargeACsvNeedsAllowLong) {
  const std::string scene = write_scene(spinning_scene(20.0, 0.01));
  const auto steps = tumble("simulate " + scene + " --dt 1e-9");
  EXPECT_EQ(steps.status, kExitInputError);
  EXPECT_THAT(steps.err, HasSubstr("tumble simulate: error: --dt: 2e+10 steps (duration 20 s / dt "
                                   "1e-09 s), more than 1e+09; give --allow-long to run it"));
  const auto csv = tumble("simulate " + scene + " --dt 1e-7 --csv " + path("x.csv"));
  EXPECT_EQ(csv.status, kExitInputError);
  EXPECT_THAT(csv.err, HasSubstr("--csv: 2e+08 steps (duration 20 s / dt 1e-07 s) write about "
                                 "2e+08 rows, 80 GB, more than 10 GB; give --every N or "
                                 "--allow-long"));
  EXPECT_EQ(directory_entries(dir_), std::vector<std::string>{"scene.json"});
  // Allowed, it starts: its CSV temporary appears (waited for, not timed, so that a slow start
  // on a loaded machine cannot kill it before its handlers are installed), then SIGTERM stops it.
  const auto allowed =
      interrupt(tumble_executable() + " simulate " + scene +
                    " --dt 1e-9 --allow-long --every 1000000 --csv " + path("x.csv"),
                "x\\.csv", "TERM");
  EXPECT_EQ(allowed.status, kExitInterrupted) << allowed.err;
  EXPECT_EQ(allowed.err, "tumble simulate: interrupted by SIGTERM; nothing written to '" +
                             path("x.csv") + "'\n");
  EXPECT_EQ(directory_entries(dir_), std::vector<std::string>{"scene.json"});
}

}  // namespace
}  // namespace tumble::app
