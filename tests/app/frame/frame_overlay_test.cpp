// The video overlay at every frame size: the share of the frame's pixels it changes (measured
// by rendering the same draw list with and without it), its text size, and what it drops when
// the frame is small.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "app/frame/frame_builder.hpp"
#include "render/overlay_layout.hpp"
#include "support/scene_builder.hpp"

namespace tumble::app {
namespace {

using ::testing::HasSubstr;

/// A brick flipping about its middle axis, with every legend item of the overlay switched on.
std::string brick_scene() {
  return testing::SceneBuilder()
      .duration(4)
      .dt(0.002)
      .integrator("rk4")
      .body(testing::BodyBuilder("brick")
                .principal({0.4, 0.9, 1.1})
                .mass(2)
                .orientation(0.9, 0.2, -0.3, 0.1)
                .angular_velocity({0.05, 3.0, 0.1}, "body"))
      .render(nlohmann::json::parse(R"({"show": {"herpolhode": true, "polhode": true}})"))
      .text();
}

/// The last frame of the brick's run at `width` x `height`, rendered with and without the
/// overlay (panels and labels).
struct OverlayShot {
  render::DrawList list;
  tumble::Image with;
  tumble::Image without;

  OverlayShot(int width, int height, double font_scale = 1.0) {
    const SceneDescription description =
        parse_scene(brick_scene(), std::string(TUMBLE_SOURCE_DIR) + "/assets/scenes/test.json");
    const CompiledScene scene = compile_scene(description, true);
    RenderSettings settings = parse_render_settings(*description.render, "test.json", {"brick"});
    settings.width = width;
    settings.height = height;
    settings.font_scale = font_scale;
    render::Renderer renderer(render::RendererOptions{width, height, 1});
    FrameBuilder builder(description, scene, settings, renderer);
    engine::Simulation simulation(scene.bodies, scene.initial, scene.settings);
    const double frame_dt = 1.0 / settings.fps;
    for (double t = 0.0; !simulation.finished(); t += frame_dt) {
      while (!simulation.finished() && simulation.time() + 1e-3 <= t) simulation.step();
      builder.observe(simulation);
    }
    list = builder.build(simulation);
    with = renderer.render(list);
    render::DrawList bare = list;
    bare.panels.clear();
    bare.labels.clear();
    without = renderer.render(bare);
  }

  /// Share of the pixels the overlay changed.
  double coverage() const {
    std::size_t changed = 0;
    for (std::size_t i = 0; i < with.rgba.size(); i += 4) {
      for (std::size_t c = 0; c < 3; ++c) {
        if (with.rgba[i + c] != without.rgba[i + c]) {
          ++changed;
          break;
        }
      }
    }
    return static_cast<double>(changed) / static_cast<double>(with.width * with.height);
  }
};

class OverlayAtSize : public ::testing::TestWithParam<std::pair<int, int>> {};

TEST_P(OverlayAtSize, CoversAtMostAFifthOfTheFrameWithReadableText) {
  const auto [width, height] = GetParam();
  const OverlayShot shot(width, height);
  ASSERT_EQ(shot.list.panels.size(), 1u);
  const render::OverlayPanel& panel = shot.list.panels[0];
  EXPECT_GE(panel.font_px, render::kMinFontPx);
  EXPECT_LE(panel.width_px, static_cast<float>(width));
  // The title, integrator and time always stay; the drift plots too down to 480x270.
  ASSERT_GE(panel.lines.size(), 2u);
  EXPECT_THAT(panel.lines[0], HasSubstr("rk4"));
  EXPECT_THAT(panel.lines[1], HasSubstr("t = 4.000 s"));
  EXPECT_EQ(panel.plots.size(), 2u);
  const double coverage = shot.coverage();
  std::printf("[ overlay  ] %dx%d: font %.0f px, %zu lines, coverage %.1f %%\n", width, height,
              static_cast<double>(panel.font_px), panel.lines.size(), 100.0 * coverage);
  EXPECT_LE(coverage, 0.20);
  EXPECT_GT(coverage, 0.02);  // it is drawn at all
}

INSTANTIATE_TEST_SUITE_P(FrameSizes, OverlayAtSize,
                         ::testing::Values(std::pair{480, 270}, std::pair{640, 360},
                                           std::pair{1280, 720}, std::pair{1920, 1080},
                                           std::pair{3840, 2160}));

TEST(FrameOverlay, TextScalesWithTheFrameAndTheFontScale) {
  EXPECT_EQ(render::overlay_font_px(1280, 720), 13.0f);
  EXPECT_EQ(render::overlay_font_px(3840, 2160), 39.0f);
  EXPECT_EQ(render::overlay_font_px(480, 270), render::kMinFontPx);  // 4.9 px floored
  EXPECT_EQ(render::overlay_font_px(1280, 720, 2.0), 26.0f);
  // A wide frame follows its height.
  EXPECT_EQ(render::overlay_font_px(2560, 720), 13.0f);
}

TEST(FrameOverlay, BigTextDropsTheLegendBeforeCoveringTheBody) {
  const OverlayShot normal(1280, 720);
  const OverlayShot big(1280, 720, 2.0);
  EXPECT_EQ(big.list.panels[0].font_px, 26.0f);
  EXPECT_LT(big.list.panels[0].lines.size(), normal.list.panels[0].lines.size());
  EXPECT_LE(big.coverage(), 0.20);
}

TEST(FrameOverlay, FontScaleIsReadAndBoundedInTheScene) {
  const auto parse = [](const char* text) {
    return parse_render_settings(nlohmann::json::parse(text), "s.json", {"brick"});
  };
  EXPECT_EQ(parse(R"({"font_scale": 1.5})").font_scale, 1.5);
  EXPECT_EQ(parse("{}").font_scale, 1.0);
  for (const char* bad : {R"({"font_scale": 20})", R"({"font_scale": 0.1})",
                          R"({"font_scale": -1})", R"({"font_scale": "big"})"}) {
    try {
      parse(bad);
      ADD_FAILURE() << bad << " accepted";
    } catch (const std::exception& error) {
      EXPECT_THAT(error.what(), HasSubstr("render.font_scale")) << bad;
    }
  }
}

}  // namespace
}  // namespace tumble::app
