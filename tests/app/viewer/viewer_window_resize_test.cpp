// `tumble view`'s window resized under Xvfb (xvfb-run): a script's `resize` asks the X server
// for a new size (SDL_SetWindowSize), and xdotool resizes it from outside as a window manager
// would. Checked on the screenshots: their size; the 3D view's projection (a flat square
// facing the camera stays square, as tall and as far off-centre as a pinhole camera of the
// scene's field of view at the new size puts it); the control panel (at most 45 % of the
// width) and its text, whose title bar and first header are font + 2 x frame padding high with
// the font at render::overlay_font_px x --font-scale; and the size, text and panel width the
// viewer reports with --stats.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "app/viewer/view_options.hpp"
#include "media/png_io.hpp"
#include "render/overlay_layout.hpp"
#include "support/command_test.hpp"
#include "support/run_command.hpp"
#include "support/scene_builder.hpp"

namespace tumble::app {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using tumble::testing::run_command;
using tumble::testing::tumble_executable;

constexpr double kFontScale = 1.5;
/// The camera: 6 m from the plate along +x, looking along -x, 0.7 m to its side (the plate is
/// drawn left of the centre, clear of the panel), 40 degrees of vertical field of view.
constexpr double kDistance = 6.0;
constexpr double kSide = 0.7;
constexpr double kFovDeg = 40.0;

/// A 1 m x 1 m plate (the equivalent box of moments 1 : 1 : 2 and mass 12 kg is 1 x 1 x
/// 0.001 m, thin along its third axis), turned so that the thin axis is world x, at rest; the
/// scene's text scale (3) is overridden by --font-scale.
nlohmann::json plate_scene() {
  const double half = std::sqrt(0.5);
  return testing::SceneBuilder()
      .duration(10.0)
      .dt(0.01)
      .body(testing::BodyBuilder("plate")
                .principal({1.0, 1.0, 2.0})
                .mass(12.0)
                .orientation(half, 0.0, half, 0.0))
      .render(
          {{"font_scale", 3.0},
           {"camera",
            {{"eye", {kDistance, kSide, 0.0}}, {"target", {0.0, kSide, 0.0}}, {"fov", kFovDeg}}},
           {"show",
            {{"overlay", false}, {"angular_velocity", false}, {"angular_momentum", false}}}})
      .json();
}

/// The plate's orange (shaded): red well above blue; the background is grey-blue.
bool plate(const std::uint8_t* p) {
  return p[0] > 90 && p[0] > p[2] + 30;
}
/// The panel's active title bar and its headers: strongly blue and dark in red (the
/// background's blue top row has more red).
bool blue(const std::uint8_t* p) {
  return p[0] < 60 && p[2] > p[0] + 45;
}

const std::uint8_t* pixel(const tumble::Image& image, int x, int y) {
  return image.rgba.data() + 4 * (static_cast<std::size_t>(y) * image.width + x);
}

/// Bounding box [x0, x1) x [y0, y1) of the plate's pixels left of `right`.
struct Box {
  int x0 = 1 << 20, y0 = 1 << 20, x1 = 0, y1 = 0;
};
Box plate_box(const tumble::Image& image, int right) {
  Box box;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < right; ++x) {
      if (!plate(pixel(image, x, y))) continue;
      box = {std::min(box.x0, x), std::min(box.y0, y), std::max(box.x1, x + 1),
             std::max(box.y1, y + 1)};
    }
  }
  return box;
}

/// Lengths of the runs of blue pixels down column `x`, top first.
std::vector<int> blue_runs(const tumble::Image& image, int x) {
  std::vector<int> runs;
  int run = 0;
  for (int y = 0; y < image.height; ++y) {
    if (blue(pixel(image, x, y))) {
      ++run;
    } else if (run > 0) {
      runs.push_back(run);
      run = 0;
    }
  }
  return runs;
}

class ViewerWindowResize : public tumble::testing::CommandTest {
 protected:
  void SetUp() override {
    CommandTest::SetUp();
    if (!viewer_available()) GTEST_SKIP() << "built without the viewer (TUMBLE_VIEWER off)";
    if (run_command("command -v xvfb-run").status != 0) {
      if (std::getenv("CI") != nullptr) FAIL() << "xvfb-run is not installed";
      GTEST_SKIP() << "xvfb-run is not installed";
    }
  }

  /// Runs `tumble view SCENE --paused --font-scale 1.5 --stats --script script.txt` (and
  /// `options`) under xvfb-run, with `beside` (shell commands) run next to it; the viewer's own
  /// status is kept in a file (xvfb-run's can be 5 under load, see view_command_test.cpp).
  tumble::testing::CommandResult view(const std::string& script, const std::string& beside = "",
                                      const std::string& options = "") {
    std::ofstream(dir_ / "script.txt") << script;
    const std::string scene = write_scene(plate_scene());
    const fs::path status_file = dir_.string() + "-status";
    fs::remove(status_file);
    auto result =
        run_command("cd '" + dir_.string() +
                    "' && xvfb-run -a -s '-screen 0 1280x800x24' sh -c '(\"$0\" view "
                    "\"$1\" --paused --font-scale 1.5 --stats --script script.txt "
                    "--output-dir . " +
                    options + " </dev/null; echo $? >\"$2\") & " + beside + " wait' '" +
                    tumble_executable() + "' '" + scene + "' '" + status_file.string() + "'");
    if (fs::exists(status_file)) {
      result.status = std::stoi(tumble::testing::read_text(status_file));
      fs::remove(status_file);
    }
    return result;
  }

  /// Checks the screenshot `name` of a `width` x `height` window.
  void expect_window(const std::string& name, int width, int height) {
    SCOPED_TRACE(name);
    const tumble::Image image = media::read_png(dir_ / name);
    ASSERT_EQ(image.width, width);
    ASSERT_EQ(image.height, height);
    const float font = render::overlay_font_px(width, height, kFontScale);
    const int padding = static_cast<int>(std::floor(3.0f * font / render::kDefaultFontPx));
    const int bar = static_cast<int>(font) + 2 * padding;

    // The panel: its title bar is the first row with blue across it, as wide as the panel.
    int top = 0;
    for (; top < height; ++top) {
      int count = 0;
      for (int x = 0; x < width; ++x) count += blue(pixel(image, x, top)) ? 1 : 0;
      if (count > width / 10) break;
    }
    ASSERT_LT(top, height) << "no panel title bar";
    int left = width;
    int right = 0;
    for (int x = 0; x < width; ++x) {
      if (!blue(pixel(image, x, top + bar / 2))) continue;
      left = std::min(left, x);
      right = std::max(right, x + 1);
    }
    const int panel = right - left;
    EXPECT_LE(panel, 0.45 * width + 1.0);
    EXPECT_NEAR(panel, std::min(std::floor(360.0 * font / 13.0), std::floor(0.45 * width)), 3.0);
    // Title bar, then the "Simulation" header below the scene's name: text and frame padding.
    const std::vector<int> runs = blue_runs(image, left + panel * 6 / 10);
    ASSERT_GE(runs.size(), 2u);
    EXPECT_NEAR(runs[0], bar, 1) << "title bar, " << font << " px text";
    EXPECT_NEAR(runs[1], bar, 1) << "header, " << font << " px text";

    // The view: a pinhole camera of the scene's vertical field of view, at this window's
    // aspect. The plate is square, 1 m over `focal` / 6 m pixels, 0.7 m left of the centre.
    const double focal = 0.5 * height / std::tan(0.5 * kFovDeg * std::numbers::pi / 180.0);
    const Box box = plate_box(image, left);
    const int plate_width = box.x1 - box.x0;
    const int plate_height = box.y1 - box.y0;
    ASSERT_GT(plate_height, 0) << "no plate left of the panel";
    EXPECT_NEAR(plate_height, focal / kDistance, 2.0);
    EXPECT_NEAR(plate_width, plate_height, 2.0) << "the 3D view's aspect is not the window's";
    EXPECT_NEAR(0.5 * (box.x0 + box.x1), 0.5 * width - focal * kSide / kDistance, 1.5);
    EXPECT_NEAR(0.5 * (box.y0 + box.y1), 0.5 * height, 1.5);
  }
};

TEST_F(ViewerWindowResize, ScriptResizesAreFollowedByTheViewThePanelAndTheText) {
  // By the frame clock: on a loaded machine a wall-clock screenshot at 0.6 s could be drawn after
  // the resize at 0.8 s.
  const auto result = view(
      "0.6 screenshot start.png\n"
      "0.8 resize 480 270\n"
      "1.4 screenshot small.png\n"
      "1.6 resize 960 720\n"
      "2.2 screenshot square.png\n"
      "2.4 resize 600 800\n"
      "3.0 screenshot tall.png\n"
      "3.2 quit\n",
      "", "--frame-clock");
  ASSERT_EQ(result.status, 0) << result.err;
  expect_window("start.png", 1280, 720);  // 20 px text: round(13 x 1.5), not the scene's 3
  expect_window("small.png", 480, 270);   // 10 px: the floor
  expect_window("square.png", 960, 720);  // 15 px
  expect_window("tall.png", 600, 800);    // 10 px
  EXPECT_THAT(result.out,
              HasSubstr("tumble view: window 600x800, text 10 px, control panel 270 px wide\n"));
  EXPECT_EQ(result.err, "");
}

TEST_F(ViewerWindowResize, AResizeFromTheWindowSystemIsFollowed) {
  if (run_command("command -v xdotool").status != 0) {
    if (std::getenv("CI") != nullptr) FAIL() << "xdotool is not installed";
    GTEST_SKIP() << "xdotool is not installed";
  }
  // xdotool waits for the window and resizes it (as a window manager would), then unmaps it
  // for half a second (nothing is drawn while the window shows nothing) and maps it again; the
  // screenshot comes after all that, by the wall clock (xdotool runs beside the viewer, so the
  // frame clock cannot order them). On a loaded machine (the sanitizer suite, two shards at once)
  // xdotool's steps once took longer than the 4 s this waited: now 6 s, and a run whose window
  // was never resized is tried once more (the output says so), as the resize is the window
  // system's, not the viewer's.
  const std::string script = "6.0 screenshot resized.png\n6.2 quit\n";
  const std::string resize =
      "xdotool search --sync --name \"^tumble view$\" windowsize --sync 720 540; sleep 0.3; "
      "xdotool search --name \"^tumble view$\" windowunmap --sync; sleep 0.5; xdotool search "
      "--name \"^tumble view$\" windowmap --sync;";
  auto result = view(script, resize);
  if (result.status == 0 && result.out.find("window 720x540") == std::string::npos) {
    std::cout << "[ retry    ] the window system did not resize the window in time: once more\n";
    result = view(script, resize);
  }
  ASSERT_EQ(result.status, 0) << result.err;
  expect_window("resized.png", 720, 540);  // 11 px text: round(13 x 0.5625 x 1.5 = 10.97)
  EXPECT_THAT(result.out, HasSubstr("tumble view: window 720x540, text 11 px"));
}

TEST(ViewerFontScale, OutOfRangeIsOneLineAndStatus1BeforeAnyWindow) {
  if (!viewer_available()) GTEST_SKIP() << "built without the viewer (TUMBLE_VIEWER off)";
  // No display: the option is refused before the viewer looks for one.
  for (const std::string value : {"20", "0.2", "-1"}) {
    const auto result = run_command("env -u DISPLAY -u WAYLAND_DISPLAY '" + tumble_executable() +
                                    "' view --font-scale " + value);
    EXPECT_EQ(result.status, 1) << value;
    EXPECT_EQ(result.err, "tumble view: --font-scale: expected a text scale from 0.25 to 8, got " +
                              value + "\n");
  }
}

}  // namespace
}  // namespace tumble::app
