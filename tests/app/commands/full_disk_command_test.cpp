// `tumble bench -o DIR` and `tumble stability -o DIR` on a full disk (issue 12): a write that
// fails, the reports' own or gnuplot's pictures (gnuplot exits 0 with half a picture), is exit
// 1 with one line naming the file by its final name, and neither DIR nor its temporary is left.
// The disk is a small tmpfs where it can be mounted (root), and a file size limit (prlimit
// --fsize: writes past it fail with EFBIG) for the file each test aims at.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/mount.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "app/support/exit_status.hpp"
#include "support/command_test.hpp"
#include "support/run_command.hpp"
#include "support/scene_builder.hpp"

namespace tumble::app {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::StartsWith;
using tumble::testing::directory_entries;
using tumble::testing::run_command;
using tumble::testing::tumble_executable;

/// A tmpfs of `size` ("64k") mounted on a new folder for the object's life: a disk that fills.
class SmallDisk {
 public:
  SmallDisk(fs::path dir, const std::string& size) : dir_(std::move(dir)) {
    fs::create_directory(dir_);
    const std::string options = "size=" + size;
    mounted_ = ::mount("tmpfs", dir_.c_str(), "tmpfs", 0, options.c_str()) == 0;
    if (!mounted_) reason_ = std::strerror(errno);
  }
  ~SmallDisk() {
    if (mounted_) ::umount2(dir_.c_str(), MNT_DETACH);
  }
  SmallDisk(const SmallDisk&) = delete;
  SmallDisk& operator=(const SmallDisk&) = delete;

  bool mounted() const { return mounted_; }
  const std::string& reason() const { return reason_; }

 private:
  fs::path dir_;
  bool mounted_ = false;
  std::string reason_;
};

class FullDisk : public testing::CommandTest {
 protected:
  void SetUp() override {
    CommandTest::SetUp();
    scene_ = write_scene(
        testing::SceneBuilder()
            .duration(1.0)
            .dt(0.01)
            .body(testing::BodyBuilder("brick").angular_velocity({0.01, 3.0, 0.01}, "body"))
            .json());
  }

  /// `tumble ARGUMENTS` with every file it writes (its captured stderr too) limited to `bytes`
  /// (SIGXFSZ left at its default: tumble must ignore it itself, or the limit kills it).
  testing::CommandResult limited(int bytes, const std::string& arguments) const {
    return run_command("prlimit --fsize=" + std::to_string(bytes) + " " + tumble_executable() +
                       " " + arguments);
  }

  /// The run failed as a full disk must fail: status 1, one error line (after any progress
  /// lines) naming `file`, inside the output `out`, and saying nothing was written there.
  static void expect_write_error(const testing::CommandResult& result, const std::string& command,
                                 const std::string& file, const std::string& out) {
    EXPECT_EQ(result.status, kExitInputError) << result.err;
    const std::string head = "tumble " + command + ": error: cannot write '" + file + "': ";
    const std::size_t at = result.err.find(head);
    ASSERT_NE(at, std::string::npos) << result.err;
    const std::string line = result.err.substr(at);
    EXPECT_EQ(line.find('\n'), line.size() - 1) << "not the last and only error line: " << line;
    EXPECT_THAT(line, HasSubstr("; nothing written to '" + out + "'\n"));
    EXPECT_EQ(result.out, "");
  }

  std::string scene_;
};

TEST_F(FullDisk, BenchOnAFullTmpfsLeavesNoFolder) {
  const SmallDisk disk(dir_ / "disk", "64k");
  if (!disk.mounted()) GTEST_SKIP() << "cannot mount a tmpfs here: " << disk.reason();
  const std::string out = path("disk/out");
  const auto result = run_command(tumble_executable() + " bench " + scene_ +
                                  " --integrators rk4 --dts 0.02,0.01 --repeat 1 -o " + out);
  EXPECT_EQ(result.status, kExitInputError) << result.err;
  EXPECT_THAT(result.err, HasSubstr("tumble bench: error: cannot write '" + out + "/"));
  EXPECT_THAT(result.err, HasSubstr("; nothing written to '" + out + "'\n"));
  EXPECT_EQ(directory_entries(dir_ / "disk"), std::vector<std::string>{});
}

TEST_F(FullDisk, BenchResultsCsvPastTheLimit) {
  // The default sweep, 50 runs: results.csv (about 15 KB) is the first file past 12 KiB.
  const auto result = limited(12288, "bench " + scene_ + " --repeat 1 -o " + path("out"));
  expect_write_error(result, "bench", path("out") + "/results.csv", path("out"));
  EXPECT_THAT(result.err, HasSubstr("results.csv': File too large;"));
  EXPECT_EQ(directory_entries(dir_), std::vector<std::string>{"scene.json"});
}

TEST_F(FullDisk, BenchPlotCutShortByGnuplot) {
  // Two runs: results.csv, report.md, the script (12-16 KB: two plots per measure) and the
  // PNGs (12-14 KB) fit in 16 KiB, the first SVG (about 28 KB) does not, and gnuplot, cut off,
  // still exits 0.
  const auto result = limited(
      16384, "bench " + scene_ + " --integrators rk4 --dts 0.02,0.01 --repeat 1 -o " + path("out"));
  expect_write_error(result, "bench", path("out") + "/scene_orientation_final.svg", path("out"));
  EXPECT_THAT(result.err, HasSubstr("the picture is incomplete"));
  EXPECT_EQ(directory_entries(dir_), std::vector<std::string>{"scene.json"});
}

TEST_F(FullDisk, StabilityOnAFullTmpfsLeavesNoFolder) {
  const SmallDisk disk(dir_ / "disk", "64k");
  if (!disk.mounted()) GTEST_SKIP() << "cannot mount a tmpfs here: " << disk.reason();
  const std::string out = path("disk/out");
  // 44 runs: CSV, report and heat map take about 80 KB.
  const auto result = run_command(tumble_executable() + " stability " + scene_ + " -o " + out);
  EXPECT_EQ(result.status, kExitInputError) << result.err;
  EXPECT_THAT(result.err, HasSubstr("tumble stability: error: cannot write '" + out + "/"));
  EXPECT_THAT(result.err, HasSubstr("; nothing written to '" + out + "'\n"));
  EXPECT_EQ(directory_entries(dir_ / "disk"), std::vector<std::string>{});
}

TEST_F(FullDisk, StabilityCsvPastTheLimit) {
  // 44 runs: stability.csv (about 7.5 KB) is past 4 KiB.
  const auto result = limited(4096, "stability " + scene_ + " -o " + path("out"));
  expect_write_error(result, "stability", path("out") + "/stability.csv", path("out"));
  EXPECT_THAT(result.err, HasSubstr("stability.csv': File too large;"));
  EXPECT_EQ(directory_entries(dir_), std::vector<std::string>{"scene.json"});
}

TEST_F(FullDisk, StabilityHeatMapCutShortByGnuplot) {
  // 4 runs: the CSV and the report fit in 4 KiB, the heat map (an 8 KB PNG) does not.
  const auto result = limited(4096, "stability " + scene_ + " --integrators rk4 -o " + path("out"));
  expect_write_error(result, "stability", path("out") + "/stability.png", path("out"));
  EXPECT_THAT(result.err, HasSubstr("the picture is incomplete"));
  EXPECT_EQ(directory_entries(dir_), std::vector<std::string>{"scene.json"});
}

}  // namespace
}  // namespace tumble::app
