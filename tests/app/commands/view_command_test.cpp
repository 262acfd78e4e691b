// Tests of `tumble view` end to end: the real window under Xvfb (xvfb-run), driven by --script
// files of timed events, checked through the screenshots and videos it writes. Without the
// viewer in the build (TUMBLE_VIEWER off), `tumble view` must say so and fail.
#include "app/commands/view_command.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "app/video/robot_picture.hpp"
#include "media/png_io.hpp"
#include "render/camera_math.hpp"
#include "support/command_test.hpp"
#include "support/image_compare.hpp"
#include "support/run_command.hpp"
#include "support/two_link_robot.hpp"

namespace tumble::app {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using tumble::testing::PixelRegion;
using tumble::testing::pixels_differing;
using tumble::testing::probe_video;
using tumble::testing::run_command;
using tumble::testing::tumble_executable;

constexpr int kViewCommandWidth = 1280;
constexpr int kViewCommandHeight = 720;
/// Left of this x the window shows the 3D view (the control panel is on the right).
constexpr int kSceneRight = 880;
/// Above this y nothing but the view and the scene's overlay (notices appear below it).
constexpr int kSceneBottom = 560;

constexpr PixelRegion kSceneRegion{0, 0, kSceneRight, kSceneBottom};
constexpr PixelRegion kPanelRegion{kViewCommandWidth - 360, 40, kViewCommandWidth - 20,
                                   kViewCommandHeight - 20};

/// Pixels of `region` matching `test(r, g, b)`.
template <typename Test>
std::size_t count_pixels(const tumble::Image& image, PixelRegion region, Test test) {
  std::size_t count = 0;
  for (int y = region.y0; y < region.y1; ++y) {
    for (int x = region.x0; x < region.x1; ++x) {
      const std::size_t i = 4 * (static_cast<std::size_t>(y) * image.width + x);
      count += test(int{image.rgba[i]}, int{image.rgba[i + 1]}, int{image.rgba[i + 2]}) ? 1 : 0;
    }
  }
  return count;
}

/// The T-handle's orange (shaded): red well above blue. The background gradient is grey-blue.
bool orange(int r, int, int b) {
  return r > 120 && r - b > 70;
}
/// ImGui's dark panels: dark and nearly grey (the view's background is a light grey-blue
/// gradient, the body orange to brown).
bool dark(int r, int g, int b) {
  return r + g + b < 200 && std::abs(r - g) < 12 && std::abs(g - b) < 12;
}

/// The window as the viewer shows it: the body (over 3000 orange pixels) in the view, and the
/// control panel on the right, whose grey background (between the blue headers and the plot
/// frames) covers at least a third of its region.
void expect_body_and_panel(const tumble::Image& window) {
  ASSERT_EQ(window.width, kViewCommandWidth);
  ASSERT_EQ(window.height, kViewCommandHeight);
  EXPECT_GT(count_pixels(window, kSceneRegion, orange), 3000u);
  const std::size_t panel_area = static_cast<std::size_t>(kPanelRegion.x1 - kPanelRegion.x0) *
                                 static_cast<std::size_t>(kPanelRegion.y1 - kPanelRegion.y0);
  EXPECT_GT(count_pixels(window, kPanelRegion, dark), panel_area / 3);
}

class ViewCommand : public tumble::testing::CommandTest {
 protected:
  void SetUp() override {
    CommandTest::SetUp();
    if (!viewer_available()) GTEST_SKIP() << "built without the viewer (TUMBLE_VIEWER off)";
    if (run_command("command -v xvfb-run").status != 0) {
      // CI installs xvfb; a missing one there is a failure, not a skip.
      if (std::getenv("CI") != nullptr) FAIL() << "xvfb-run is not installed";
      GTEST_SKIP() << "xvfb-run is not installed";
    }
  }

  /// Runs the viewer under Xvfb with `script` (written to the test's folder), outputs there.
  /// Runs `tumble view ARGUMENTS --script` (SCRIPT) under xvfb-run. The status returned is the
  /// viewer's own, kept in a file: xvfb-run's can be 5 when Xvfb's SIGUSR1 at its reset
  /// interrupts the removal of xvfb-run's temporary folder (seen under ctest -j2).
  tumble::testing::CommandResult view(const std::string& script, const std::string& arguments) {
    std::ofstream(dir_ / "script.txt") << script;
    const fs::path status_file = dir_.string() + "-status";
    fs::remove(status_file);
    auto result =
        run_command("cd '" + dir_.string() +
                    "' && xvfb-run -a -s '-screen 0 1280x800x24' sh -c '\"$0\" view "
                    "\"$@\" --script script.txt --output-dir . </dev/null; echo $? >" +
                    status_file.string() + "' '" + tumble_executable() + "' " + arguments);
    if (fs::exists(status_file)) {
      result.status = std::stoi(tumble::testing::read_text(status_file));
      fs::remove(status_file);
    }
    return result;
  }

  tumble::Image shot(const std::string& name) const { return media::read_png(dir_ / name); }

  std::string demo() const {
    return std::string(TUMBLE_SOURCE_DIR) + "/assets/scenes/t_handle_flip.json";
  }
};

TEST_F(ViewCommand, DrawsTheBodyAndThePanelsAndSpacePauses) {
  const auto result = view(
      "1.0 screenshot playing1.png\n"
      "1.4 screenshot playing2.png\n"
      "1.5 key space\n"
      "1.9 screenshot paused1.png\n"
      "2.4 screenshot paused2.png\n"
      "2.5 key space\n"
      "2.9 screenshot resumed.png\n"
      "3.0 quit\n",
      "--frame-clock '" + demo() + "'");
  ASSERT_EQ(result.status, 0) << result.err;

  // The script's times are on the viewer's frame clock (frame 30, 42, ...): however slowly the
  // machine draws, 12 frames of 1/30 s of simulation lie between the two playing screenshots.
  // The body is drawn in the view and the control panel on the right, not over the view.
  const tumble::Image playing1 = shot("playing1.png");
  expect_body_and_panel(playing1);
  EXPECT_EQ(count_pixels(playing1, PixelRegion{340, 240, kSceneRight, kSceneBottom}, dark), 0u)
      << "no panel over the middle of the view";

  // Playing: the body moves between screenshots; paused: the view is identical; Space again
  // resumes.
  const tumble::Image paused1 = shot("paused1.png");
  EXPECT_GT(pixels_differing(playing1, shot("playing2.png"), 0, kSceneRegion), 500u);
  EXPECT_EQ(pixels_differing(paused1, shot("paused2.png"), 0, kSceneRegion), 0u);
  EXPECT_GT(pixels_differing(paused1, shot("resumed.png"), 0, kSceneRegion), 500u);
}

TEST_F(ViewCommand, RightStepsWhilePausedAndBackspaceResets) {
  const auto result = view(
      "0.8 screenshot start.png\n"
      "1.0 key right\n"
      "1.3 screenshot stepped.png\n"
      "1.5 key backspace\n"
      "1.8 screenshot reset.png\n"
      "2.0 quit\n",
      "--paused '" + demo() + "'");
  ASSERT_EQ(result.status, 0) << result.err;
  const tumble::Image start = shot("start.png");
  // One 1 ms step turns the body a little (w ~ 10 rad/s: about half a degree).
  EXPECT_GT(pixels_differing(start, shot("stepped.png"), 0, kSceneRegion), 20u);
  // Reset returns to the first frame exactly.
  EXPECT_EQ(pixels_differing(start, shot("reset.png"), 0, kSceneRegion), 0u);
}

TEST_F(ViewCommand, DragOrbitsTheCameraButNotOverAPanel) {
  const auto result = view(
      "0.8 screenshot before.png\n"
      "1.0 drag 400 400 520 380\n"
      "1.5 screenshot orbited.png\n"
      "1.6 drag 1100 600 1000 560\n"
      "2.1 screenshot over_panel.png\n"
      "2.2 wheel 3\n"
      "2.5 screenshot wheel_over_panel.png\n"
      "2.6 move 450 300\n"
      "2.7 wheel 3\n"
      "3.0 screenshot zoomed.png\n"
      "3.1 quit\n",
      "--paused '" + demo() + "'");
  ASSERT_EQ(result.status, 0) << result.err;
  const tumble::Image orbited = shot("orbited.png");
  EXPECT_GT(pixels_differing(shot("before.png"), orbited, 0, kSceneRegion), 2000u);
  EXPECT_EQ(pixels_differing(orbited, shot("over_panel.png"), 0, kSceneRegion), 0u);
  EXPECT_EQ(pixels_differing(orbited, shot("wheel_over_panel.png"), 0, kSceneRegion), 0u);
  // Zooming in (three notches: 1.15^3 = 1.52 times closer) makes the body bigger.
  EXPECT_GT(count_pixels(shot("zoomed.png"), kSceneRegion, orange),
            count_pixels(orbited, kSceneRegion, orange) * 3 / 2);
}

TEST_F(ViewCommand, CtrlPWritesAScreenshotAndCtrlRRecordsAVideo) {
  const auto result = view(
      "0.5 key ctrl+r\n"
      "2.5 key ctrl+r\n"
      "2.7 key ctrl+p\n"
      "3.0 quit\n",
      "--frame-clock '" + demo() + "'");
  ASSERT_EQ(result.status, 0) << result.err;
  // Named after the scene, in the output folder.
  // The screenshot is the window: the view with the body, and the control panel.
  expect_body_and_panel(shot("t_handle_flip-1.png"));
  const std::string probe = probe_video(path("t_handle_flip-1.mp4"));
  ASSERT_THAT(probe, HasSubstr("h264,1280,720,"));
  // On the frame clock Ctrl+R comes at frame 15 and again at frame 75: 60 frames drawn while
  // recording, each 1/30 s of the viewer's time, and the first frame of the recording (the one
  // frame either way is the rounding of the summed 1/30 s), however slowly they were drawn.
  const int frames = std::stoi(probe.substr(probe.rfind(',') + 1));
  EXPECT_NEAR(frames, 61, 1);
}

TEST_F(ViewCommand, AnInterruptDiscardsTheRecordingAndExitsWith130) {
  // Ctrl+R records to t_handle_flip-1.mp4 through `.t_handle_flip-1.mp4.tmp-PID`; once that
  // temporary is there (waited for, not timed: the viewer may start slowly under load), the
  // signal goes to PID, the viewer itself. The script's quit only ends a run that missed it.
  // The viewer's own status is kept in a file: xvfb-run's can be 5 when Xvfb's SIGUSR1 at its
  // reset interrupts the removal of xvfb-run's temporary folder.
  std::ofstream(dir_ / "script.txt") << "0.2 key ctrl+r\n60 quit\n";
  const fs::path status_file = dir_.string() + "-status";
  for (const std::string signal : {"INT", "TERM"}) {
    const auto result = run_command(
        "cd '" + dir_.string() + "' && (env --default-signal=INT xvfb-run -a -s '-screen 0 " +
        "1280x800x24' sh -c '\"$0\" view \"$1\" --script script.txt --output-dir . </dev/null; "
        "echo $? >\"$2\"' '" +
        tumble_executable() + "' '" + demo() + "' '" + status_file.string() +
        "' & pid=$!; tmp=; for i in $(seq 1500); do tmp=$(ls -a | grep "
        "'^\\.t_handle_flip-1\\.mp4\\.tmp-' | head -n 1); [ -n \"$tmp\" ] && break; sleep "
        "0.02; done; sleep 0.3; kill -" +
        signal + " \"${tmp##*-}\"; wait $pid)");
    EXPECT_EQ(tumble::testing::read_text(status_file), "130\n") << result.err;
    fs::remove(status_file);
    EXPECT_THAT(result.err, HasSubstr("tumble view: interrupted by SIG" + signal +
                                      "; recording discarded, nothing written to "
                                      "'./t_handle_flip-1.mp4'\n"));
    EXPECT_EQ(tumble::testing::directory_entries(dir_), std::vector<std::string>{"script.txt"});
  }
}

TEST_F(ViewCommand, ABadDroppedFileShowsAnErrorAndTheViewerKeepsRunning) {
  std::ofstream(dir_ / "broken.obj") << "v 0 0 0\nv 1 0 0\nf 1 2 3\n";
  const auto result = view(
      "0.5 drop missing_mesh.stl\n"
      "0.8 drop broken.obj\n"
      "1.2 screenshot after.png\n"
      "1.4 drop " +
          std::string(TUMBLE_SOURCE_DIR) +
          "/assets/meshes/tennis_racket.obj\n"
          "2.0 screenshot racket.png\n"
          "2.2 quit\n",
      "'" + demo() + "'");
  ASSERT_EQ(result.status, 0) << result.err;
  // The errors stayed in the window until it closed, and are repeated on stderr then.
  EXPECT_THAT(result.err, HasSubstr("missing_mesh.stl"));
  EXPECT_THAT(result.err, HasSubstr("broken.obj"));
  // Still drawing the T-handle after the bad drops, then the racket.
  EXPECT_GT(count_pixels(shot("after.png"), kSceneRegion, orange), 3000u);
  EXPECT_GT(pixels_differing(shot("after.png"), shot("racket.png"), 0, kSceneRegion), 5000u);
}

TEST_F(ViewCommand, PanelButtonsPlayPauseAndReset) {
  // The control panel's first row at 1280x720: Play/Pause at (952, 103), Reset at (1061, 103).
  const auto result = view(
      "0.8 screenshot start.png\n"
      "1.0 click 952 103\n"
      "1.5 screenshot playing1.png\n"
      "1.9 screenshot playing2.png\n"
      "2.0 click 952 103\n"
      "2.4 screenshot paused1.png\n"
      "2.8 screenshot paused2.png\n"
      "3.0 click 1061 103\n"
      "3.4 screenshot reset.png\n"
      "3.5 quit\n",
      "--paused '" + demo() + "'");
  ASSERT_EQ(result.status, 0) << result.err;
  const tumble::Image start = shot("start.png");
  EXPECT_GT(pixels_differing(shot("playing1.png"), shot("playing2.png"), 0, kSceneRegion), 500u);
  EXPECT_EQ(pixels_differing(shot("paused1.png"), shot("paused2.png"), 0, kSceneRegion), 0u);
  EXPECT_GT(pixels_differing(start, shot("paused1.png"), 0, kSceneRegion), 500u);
  EXPECT_EQ(pixels_differing(start, shot("reset.png"), 0, kSceneRegion), 0u);
}

TEST_F(ViewCommand, CtrlOOpensTheFilesSectionWhoseRecordButtonRecordsTheView) {
  // Ctrl+O opens the Files section (drawn closed until then); at 1280x720 its record field is
  // at (1030, 686), Record at (1183, 686), and then Stop recording at (960, 686). The button
  // is pressed while the panels are drawn, after the frame's scene image was or was not asked
  // for: the recording must still hold the view alone, from its first frame.
  const auto result = view(
      "0.5 key ctrl+o\n"
      "0.8 click 1030 686\n"
      "1.0 type frames/\n"
      "1.2 click 1183 686\n"
      "2.2 click 960 686\n"
      "2.6 quit\n",
      "--frame-clock --paused '" + demo() + "'");
  ASSERT_EQ(result.status, 0) << result.err;
  const std::vector<std::string> frames = tumble::testing::directory_entries(path("frames"));
  // On the frame clock Record (released at frame 38) to Stop (released at frame 68): 30 frames
  // of 1/30 s and the first, give or take the frame a panel button takes to start a recording.
  EXPECT_NEAR(static_cast<double>(frames.size()), 31.0, 2.0);
  for (const char* name : {"frame_000000.png", "frame_000010.png"}) {
    const tumble::Image frame = shot(std::string("frames/") + name);
    EXPECT_EQ(frame.width, kViewCommandWidth);
    EXPECT_GT(count_pixels(frame, kSceneRegion, orange), 3000u) << name;
    EXPECT_EQ(count_pixels(frame, kPanelRegion, dark), 0u) << name << ": panels recorded";
  }
}

TEST_F(ViewCommand, IntegratorPanelAddsARunBeside) {
  // Integrator section at 1280x720: the dt list at (1040, 223) with 0.01 at (1045, 350),
  // "beside the current runs" at (927, 246), Apply at (973, 269).
  const auto result = view(
      "0.8 screenshot one_run.png\n"
      "1.0 click 1040 223\n"
      "1.3 click 1045 350\n"
      "1.6 click 927 246\n"
      "1.9 click 973 269\n"
      "2.2 key space\n"
      "3.2 screenshot two_runs.png\n"
      "3.3 quit\n",
      "--paused '" + demo() + "'");
  ASSERT_EQ(result.status, 0) << result.err;
  // The run beside is drawn in translucent green over the scene.
  const auto green = [](int r, int g, int b) { return g > r + 40 && g > b + 40; };
  EXPECT_EQ(count_pixels(shot("one_run.png"), kSceneRegion, green), 0u);
  EXPECT_GT(count_pixels(shot("two_runs.png"), kSceneRegion, green), 1000u);
}

TEST_F(ViewCommand, RealKeyPressesFromXdotoolReachTheViewer) {
  // The script only takes screenshots; the keys come from the X server, through SDL's events.
  if (run_command("command -v xdotool").status != 0) {
    if (std::getenv("CI") != nullptr) FAIL() << "xdotool is not installed";
    GTEST_SKIP() << "xdotool is not installed";
  }
  std::ofstream(dir_ / "script.txt") << "1.0 screenshot playing.png\n"
                                        "4.0 screenshot paused1.png\n"
                                        "4.5 screenshot paused2.png\n"
                                        "6.0 quit\n";
  // Space once the viewer has taken playing.png (at most 60 s): its script clock starts with its
  // window, which under AddressSanitizer and load took over 2.5 s to open, and a fixed wait from
  // the launch then paused it before that screenshot. paused1.png at 4.0 s comes 3 s after.
  const std::string keys =
      "timeout 60 sh -c 'until [ -e playing.png ]; do sleep 0.1; done'; "
      "xdotool search --sync --name '^tumble view$' windowfocus --sync key space; "
      "sleep 1; xdotool search --name '^tumble view$' windowfocus --sync key ctrl+p";
  const auto result =
      run_command("cd '" + dir_.string() + "' && xvfb-run -a -s '-screen 0 1280x800x24' sh -c \"'" +
                  tumble_executable() + "' view '" + demo() +
                  "' --script script.txt --output-dir . </dev/null & " + keys + "; wait\"");
  ASSERT_EQ(result.status, 0) << result.err;
  const tumble::Image paused1 = shot("paused1.png");
  EXPECT_EQ(pixels_differing(paused1, shot("paused2.png"), 0, kSceneRegion), 0u);
  EXPECT_GT(pixels_differing(shot("playing.png"), paused1, 0, kSceneRegion), 500u);
  // Ctrl+P, with the modifier from the keyboard state.
  EXPECT_EQ(shot("t_handle_flip-1.png").width, kViewCommandWidth);
}

TEST_F(ViewCommand, OpensARobotFileAndAClickOnALinkShowsItsInertials) {
  // The arm of the two-link robot, where the viewer's first frame shows it.
  const fs::path robot = dir_ / "two_link.urdf";
  std::ofstream(robot) << testing::kTwoLinkUrdf;
  const RobotPicture picture = load_robot_picture(robot, {});
  const Eigen::Vector3f arm = render::project_to_pixels(
      robot_camera(picture, kViewCommandWidth, kViewCommandHeight), kViewCommandWidth,
      kViewCommandHeight, testing::kTwoLinkArmCenter.cast<float>());
  ASSERT_LT(arm.x(), kSceneRight);
  const std::string at = std::to_string(arm.x()) + " " + std::to_string(arm.y());
  const auto result = view(
      "0.5 screenshot before.png\n0.6 click " + at + "\n1.0 screenshot selected.png\n1.1 quit\n",
      "--frame-clock '" + robot.string() + "'");
  ASSERT_EQ(result.status, 0) << result.err;

  // The selected link turns yellow in the view; the panel's inspector opens on it (more of
  // the panel is text: the two inertials' table).
  const auto yellow = [](int r, int g, int b) { return r > 180 && g > 150 && b < 140; };
  const tumble::Image before = shot("before.png");
  const tumble::Image selected = shot("selected.png");
  EXPECT_LT(count_pixels(before, kSceneRegion, yellow), 20u);
  EXPECT_GT(count_pixels(selected, kSceneRegion, yellow), 300u);
  EXPECT_GT(pixels_differing(before, selected, 0, kPanelRegion), 500u);
}

TEST_F(ViewCommand, WithoutADisplayItSaysSoAndFails) {
  const auto result =
      run_command("env -u DISPLAY -u WAYLAND_DISPLAY '" + tumble_executable() + "' view");
  EXPECT_EQ(result.status, 1);
  EXPECT_THAT(result.err, HasSubstr("no display"));
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1);
}

TEST_F(ViewCommand, BadOptionsFailBeforeAnyWindowOpens) {
  const std::string exe = "env -u DISPLAY '" + tumble_executable() + "' view ";
  std::ofstream(dir_ / "bad_script.txt") << "0.5 key nosuchkey\n";
  const auto bad_script = run_command(exe + "--script '" + path("bad_script.txt") + "'");
  EXPECT_EQ(bad_script.status, 1);
  EXPECT_THAT(bad_script.err, HasSubstr("bad_script.txt:1"));
  const auto bad_size = run_command(exe + "--size 0x10");
  EXPECT_EQ(bad_size.status, 1);
  EXPECT_THAT(bad_size.err, HasSubstr("--size"));
  const auto bad_dir = run_command(exe + "--output-dir /nonexistent/folder");
  EXPECT_EQ(bad_dir.status, 1);
  EXPECT_THAT(bad_dir.err, HasSubstr("--output-dir"));
  const auto bad_integrator = run_command(exe + "--integrator leapfrog");
  EXPECT_EQ(bad_integrator.status, 1);
  EXPECT_THAT(bad_integrator.err, HasSubstr("--integrator: unknown integrator \"leapfrog\""));
}

TEST(ViewCommandBuild, WithoutTheViewerItSaysSo) {
  if (viewer_available()) GTEST_SKIP() << "this build has the viewer";
  const auto result = run_command("'" + tumble_executable() + "' view");
  EXPECT_EQ(result.status, 1);
  EXPECT_THAT(result.err, HasSubstr("this build has no viewer"));
}

}  // namespace
}  // namespace tumble::app
