// Tests of `tumble compare`: the option parsers and grid layout directly, and the executable end
// to end (videos checked with ffprobe, PNG frames pixel by pixel, errors by their message).
#include "app/commands/compare_command.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "base/errors.hpp"
#include "base/image.hpp"
#include "media/png_io.hpp"
#include "support/command_test.hpp"
#include "support/image_compare.hpp"
#include "support/input_error.hpp"
#include "support/run_command.hpp"
#include "support/scene_builder.hpp"

namespace tumble::app {
namespace {

using ::testing::HasSubstr;
using tumble::testing::fraction_differing;
using tumble::testing::fresh_directory;
using tumble::testing::run_command;
using tumble::testing::tumble_executable;

/// A chunky box (moments 2, 3, 4) spun about its intermediate axis with a small wobble: the
/// tumble amplifies integrator errors, so a first-order method ends far from a fourth-order one.
nlohmann::json tumbling_scene() {
  return testing::SceneBuilder()
      .name("compare tumble")
      .duration(3.0)
      .dt(0.01)
      .body(testing::BodyBuilder("brick").principal({2, 3, 4}).angular_velocity({0.2, 5.0, 0.2},
                                                                                "body"))
      .json();
}

/// The w x h block of `image` whose top-left corner is (x, y).
tumble::Image crop(const tumble::Image& image, int x, int y, int w, int h) {
  tumble::Image out;
  out.width = w;
  out.height = h;
  for (int row = y; row < y + h; ++row) {
    const std::uint8_t* begin = image.pixel(x, row);
    out.rgba.insert(out.rgba.end(), begin, begin + 4 * w);
  }
  return out;
}

class CompareCommand : public testing::CommandTest {
 protected:
  static testing::CommandResult compare(const std::string& arguments) {
    return run_command(tumble_executable() + " compare " + arguments);
  }

  /// Names in the test folder other than the scene files.
  std::vector<std::string> outputs() const {
    std::vector<std::string> names = testing::directory_entries(dir_);
    std::erase_if(names, [](const std::string& name) { return name.ends_with(".json"); });
    return names;
  }
};

TEST(CompareOptionsParsing, IntegratorListNeedsTwoOrMoreKnownDistinctNames) {
  EXPECT_EQ(comparison_integrators("rk4,splitting4,exact"),
            (std::vector<std::string>{"rk4", "splitting4", "exact"}));
  const auto message = [](const std::string& text) {
    return testing::input_error_of([&] { comparison_integrators(text); }, text);
  };
  EXPECT_THAT(message("rk4,nope"), HasSubstr("--integrators: unknown integrator 'nope'"));
  EXPECT_THAT(message("rk4"), HasSubstr("at least two integrators"));
  EXPECT_THAT(message("rk4,rk4"), HasSubstr("'rk4' is given twice"));
  EXPECT_THAT(message("rk4,,exact"), HasSubstr("without empty items"));
  EXPECT_EQ(parse_compare_layout("grid"), CompareLayout::kGrid);
  EXPECT_EQ(parse_compare_layout("overlay"), CompareLayout::kOverlay);
  EXPECT_THROW(parse_compare_layout("stack"), tumble::InputError);
}

TEST(CompareGrid, IsNearSquareWithEqualEvenTilesCentred) {
  const GridLayout two = grid_layout(2, 1280, 720);
  EXPECT_EQ(two.columns, 2);
  EXPECT_EQ(two.rows, 1);
  EXPECT_EQ(two.tile_width, 640);
  EXPECT_EQ(two.tile_height, 720);
  const GridLayout three = grid_layout(3, 1280, 720);
  EXPECT_EQ(three.columns * 10 + three.rows, 22);
  EXPECT_EQ(three.tile_width, 640);
  EXPECT_EQ(three.tile_height, 360);
  EXPECT_EQ(grid_layout(4, 1280, 720).columns * 10 + grid_layout(4, 1280, 720).rows, 22);
  EXPECT_EQ(grid_layout(5, 1280, 720).columns * 10 + grid_layout(5, 1280, 720).rows, 32);
  EXPECT_EQ(grid_layout(9, 1280, 720).columns * 10 + grid_layout(9, 1280, 720).rows, 33);
  // 1280 / 3 = 426.67: tiles of 426 (even), the 2 spare pixels split on both sides.
  const GridLayout five = grid_layout(5, 1280, 722);
  EXPECT_EQ(five.tile_width, 426);
  EXPECT_EQ(five.tile_height, 360);
  EXPECT_EQ(five.left, 1);
  EXPECT_EQ(five.top, 1);
  EXPECT_THROW(grid_layout(9, 40, 40), tumble::InputError);
}

TEST_F(CompareCommand, GridVideoHasTheFrameSizeAndFrameCount) {
  const std::string scene = write_scene(tumbling_scene());
  const auto result = compare(scene + " --integrators rk4,splitting4,seed-semi-implicit -o '" +
                              path("grid.mp4") + "' --size 320x180 --fps 5");
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("3 integrators, 16 frames (grid 2x2)"));
  // 3 s at 5 fps: 16 frames.
  EXPECT_EQ(testing::probe_video(path("grid.mp4")), "h264,320,180,16");
  EXPECT_EQ(outputs(), (std::vector<std::string>{"grid.mp4"}));
}

TEST_F(CompareCommand, GridTilesDifferWhereTheIntegratorsDo) {
  // Three runs in a 2x2 grid of 320x240 tiles; the last frame (t = 3 s) only.
  const std::string scene = write_scene(tumbling_scene());
  const auto result =
      compare(scene + " --integrators seed-semi-implicit,rk4,splitting4 --dt 0.02 -o '" +
              path("frames") + "/' --size 640x480 --frames 90: --quiet");
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_EQ(result.out, "");
  const tumble::Image frame = media::read_png(dir_ / "frames" / "frame_000090.png");
  ASSERT_EQ(frame.width, 640);
  ASSERT_EQ(frame.height, 480);

  // The body region of each tile: below its label panel.
  const auto body = [&](int column, int row) {
    return crop(frame, column * 320, row * 240 + 110, 320, 130);
  };
  const tumble::Image seed = body(0, 0);
  const tumble::Image rk4 = body(1, 0);
  const tumble::Image splitting4 = body(0, 1);
  const tumble::Image empty = body(1, 1);
  // seed-semi-implicit has tumbled elsewhere; rk4 and splitting4 agree to a few pixels.
  EXPECT_GT(fraction_differing(seed, rk4, 24), 0.02);
  EXPECT_LT(fraction_differing(rk4, splitting4, 24), 0.002);
  // The fourth tile is empty: one flat grey.
  EXPECT_LT(fraction_differing(empty, crop(frame, 320, 240, 320, 130), 0), 1e-9);
  EXPECT_GT(fraction_differing(empty, rk4, 24), 0.5);
}

TEST_F(CompareCommand, OverlayShowsEachRunInItsColourOverTheGhost) {
  // Explicit Euler and seed-semi-implicit at a large step both leave the exact solution.
  const std::string scene = write_scene(tumbling_scene());
  const auto result = compare(scene +
                              " --integrators explicit-euler,seed-semi-implicit --dt 0.1 --layout "
                              "overlay -o '" +
                              path("frames") + "/' --size 640x360 --frames 90: -q");
  ASSERT_EQ(result.status, 0) << result.err;
  const tumble::Image frame = media::read_png(dir_ / "frames" / "frame_000090.png");
  ASSERT_EQ(frame.width, 640);

  // Outside the legend (top-left), classify the pixels that are not the row's background (the
  // gradient, read at the right edge): orange (first run), green (second) or neither (ghost).
  std::size_t orange = 0;
  std::size_t green = 0;
  std::size_t ghost = 0;
  for (int y = 0; y < frame.height; ++y) {
    const std::uint8_t* background = frame.pixel(frame.width - 1, y);
    for (int x = 0; x < frame.width; ++x) {
      if (x < 330 && y < 130) continue;
      const std::uint8_t* p = frame.pixel(x, y);
      const int r = p[0];
      const int g = p[1];
      const int b = p[2];
      bool plain = true;
      for (int c = 0; c < 3; ++c) plain = plain && std::abs(int{p[c]} - int{background[c]}) <= 6;
      if (plain) continue;
      if (r > b + 30 && r > g) {
        ++orange;
      } else if (g > b + 5 && g > r + 10) {
        ++green;
      } else if (std::abs(r - g) < 40 && b > r) {  // the background's tint, darkened
        ++ghost;
      }
    }
  }
  EXPECT_GT(orange, 500u);
  EXPECT_GT(green, 500u);
  EXPECT_GT(ghost, 200u) << orange << " orange, " << green << " green";
}

TEST_F(CompareCommand, ABlownUpRunFreezesAndGivesStatusThreeWithAWarning) {
  const std::string scene = write_scene(testing::fast_needle_scene());
  const auto result = compare(scene + " --integrators explicit-euler,rk4 -o '" +
                              path("needle.mp4") + "' --size 320x180 --fps 10");
  EXPECT_EQ(result.status, 3) << result.err;
  EXPECT_THAT(result.err, HasSubstr("tumble compare: warning: explicit-euler blew up: body "
                                    "'needle' at step 241 (t = 2.41 s)"));
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  // Complete: 3 s at 10 fps.
  EXPECT_EQ(testing::probe_video(path("needle.mp4")), "h264,320,180,31");
}

TEST_F(CompareCommand, ErrorsAreOneLineWithStatusOneAndLeaveNothing) {
  const std::string scene = write_scene(tumbling_scene());
  const std::string out = " -o '" + path("out.mp4") + "' --size 160x90";
  const auto expect_error = [&](const std::string& arguments, const std::string& message) {
    const auto result = compare(arguments);
    EXPECT_EQ(result.status, 1) << arguments;
    EXPECT_THAT(result.err, HasSubstr(message)) << arguments;
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
    EXPECT_EQ(outputs(), std::vector<std::string>{}) << arguments;
  };
  expect_error(scene + " --integrators rk4,warp" + out,
               "tumble compare: error: --integrators: unknown integrator 'warp'");
  expect_error(scene + " --integrators rk4" + out, "at least two integrators");
  expect_error(scene + " --integrators rk4,exact,rk4" + out, "'rk4' is given twice");
  expect_error(scene + " --integrators rk4,exact --layout stacked" + out,
               "--layout: expected grid or overlay, got \"stacked\"");
  expect_error(scene + " --integrators rk4,exact -o '" + path("missing/out.mp4") + "'", "missing");
  expect_error(scene + " --integrators rk4,exact --dt -1" + out, "--dt");
}

}  // namespace
}  // namespace tumble::app
