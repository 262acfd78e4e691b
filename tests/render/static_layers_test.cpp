// Frames started from the stored static layers (background, unshadowed ground) against the same
// frames drawn layer by layer: equal pixel for pixel, over a run with a moving body, a moving
// shadow, lines, points, a translucent body and text, with and without the filter and
// multisampling, and across camera, style and size changes that must redraw the layers.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <string>
#include <vector>

#include "render/renderer.hpp"
#include "render_support.hpp"

namespace tumble::render {
namespace {

using testing::box_mesh;

constexpr int kLayersWidth = 200;
constexpr int kLayersHeight = 150;

/// What a run shows besides its bodies.
struct RunKind {
  bool ground = false;
  bool label = true;
  bool jumping = false;  // the box jumps from side to side, without a trail
  bool panel = false;    // a titled panel whose text and plot change every frame
  int width = kLayersWidth;
  int height = kLayersHeight;
};

/// Frame `i` of a run: a box tumbling over the ground (when `ground`), a translucent box, an
/// arrow, a trail, points and a label; the camera moves from frame 6 on and the background
/// changes at frame 9. `jumping`: the box jumps from side to side and there is no trail, so the
/// drawn box moves and shrinks as well as grows. `panel`: in the top-left corner, then from
/// frame 4 to 5 over the bodies, and wider from frame 10 on.
DrawList layered_frame(MeshId box, int i, const RunKind& kind) {
  const bool ground = kind.ground, label = kind.label, jumping = kind.jumping;
  DrawList frame;
  frame.camera.eye = {3.0f, -4.0f, 2.5f};
  if (i >= 6) frame.camera.eye.x() += 0.1f * static_cast<float>(i - 5);
  frame.camera.target = {0.0f, 0.0f, 0.3f};
  if (i >= 9) frame.style.background_top = {0.2f, 0.25f, 0.5f, 1.0f};
  frame.style.ground = ground;
  frame.style.ground_height = -1.0f;
  const float angle = 0.35f * static_cast<float>(i);
  const Eigen::Vector3f centre =
      jumping ? Eigen::Vector3f(i % 2 == 0 ? -1.6f : 1.4f, 0.0f, 0.4f * static_cast<float>(i % 3))
              : Eigen::Vector3f(0.3f * std::sin(angle), 0.0f, 0.2f);
  testing::add_run_solids(frame, box, centre, angle);
  Polyline trail;
  for (int k = 0; k <= i && !jumping; ++k) {
    trail.points.emplace_back(0.1f * static_cast<float>(k), -0.5f, 0.1f * static_cast<float>(k));
  }
  frame.polylines.push_back(trail);
  frame.points.push_back({{Eigen::Vector3f(0.5f, -0.5f, 0.8f)}, {1.0f, 1.0f, 0.0f, 1.0f}, 6.0f});
  if (kind.panel) {
    OverlayPanel panel;
    panel.title = "run";
    panel.position_px =
        i == 4 || i == 5 ? Eigen::Vector2f(90.0f, 60.0f) : Eigen::Vector2f(4.0f, 4.0f);
    panel.width_px = i >= 10 ? 90.0f : 70.0f;
    panel.lines = {"t = " + std::to_string(i), "fixed"};
    Plot plot;
    for (int k = 0; k <= i; ++k) plot.values.push_back(std::sin(0.7f * static_cast<float>(k)));
    plot.height_px = 16.0f;
    panel.plots.push_back(plot);
    frame.panels.push_back(panel);
  }
  if (label) {
    Label text;
    text.text = "frame " + std::to_string(i);
    text.screen_px = {8.0f, 8.0f};
    frame.labels.push_back(text);
  }
  return frame;
}

/// Renders the run twice, with and without stored layers, and compares every frame.
void expect_runs_equal(RendererOptions options, const RunKind& kind) {
  options.width = kind.width;
  options.height = kind.height;
  RendererOptions drawn_options = options;
  drawn_options.reuse_static_layers = false;
  Renderer reused(options);
  Renderer drawn(drawn_options);
  const MeshId reused_box = reused.upload(box_mesh({0.5f, 0.4f, 0.3f}));
  const MeshId drawn_box = drawn.upload(box_mesh({0.5f, 0.4f, 0.3f}));
  for (int i = 0; i < 12; ++i) {
    if (i == 10) {  // a new size, then back: the stored copy is made again
      reused.resize(kind.width + 20, kind.height);
      reused.resize(kind.width, kind.height);
    }
    const Image a = reused.render(layered_frame(reused_box, i, kind));
    const Image b = drawn.render(layered_frame(drawn_box, i, kind));
    ASSERT_EQ(a.width, b.width);
    ASSERT_EQ(a.height, b.height);
    std::size_t differing = 0;
    for (std::size_t k = 0; k < a.rgba.size(); ++k) differing += a.rgba[k] != b.rgba[k];
    EXPECT_EQ(differing, 0u) << "frame " << i;
  }
}

TEST(StaticLayers, GroundAndShadowFramesEqualThoseDrawnLayerByLayer) {
  expect_runs_equal(RendererOptions{}, {.ground = true});
}

TEST(StaticLayers, BackgroundOnlyFramesEqualThoseDrawnLayerByLayer) {
  expect_runs_equal(RendererOptions{}, {.ground = false});
}

// Without a ground, a frame restores only the box the last one drew in: with the overlay drawn
// into the scene's framebuffer (no filter), after the filter, and with nothing but the scene.
TEST(StaticLayers, BackgroundOnlyFramesRestoringTheLastDrawnBoxEqualThoseDrawnLayerByLayer) {
  RendererOptions filtered;
  filtered.filter = AntialiasingFilter::fxaa;
  expect_runs_equal(filtered, {.ground = false});
  expect_runs_equal(RendererOptions{}, {.ground = false, .label = false});
  expect_runs_equal(filtered, {.ground = false, .label = false});
  for (const bool label : {false, true}) {
    expect_runs_equal(RendererOptions{}, {.ground = false, .label = label, .jumping = true});
    expect_runs_equal(filtered, {.ground = false, .label = label, .jumping = true});
  }
}

// A panel's decorations stored over the layers and copied back while they and what lies under
// them stay (after the filter, without a ground); drawn again where it moves, widens or lies
// over the bodies.
TEST(StaticLayers, PanelsOverStoredLayersEqualThoseDrawnLayerByLayer) {
  RendererOptions filtered;
  filtered.filter = AntialiasingFilter::fxaa;
  for (const bool jumping : {false, true}) {
    // At 400x300 the bodies lie clear of the corner's panel (but for some of the jumps).
    const RunKind kind{.jumping = jumping, .panel = true, .width = 400, .height = 300};
    expect_runs_equal(filtered, kind);
    expect_runs_equal(RendererOptions{}, kind);
  }
  expect_runs_equal(filtered, {.ground = true, .panel = true, .width = 400, .height = 300});
}

TEST(StaticLayers, FilteredFramesEqualThoseDrawnLayerByLayer) {
  RendererOptions options;
  options.filter = AntialiasingFilter::fxaa;
  expect_runs_equal(options, {.ground = true});
}

TEST(StaticLayers, MultisampledFramesEqualThoseDrawnLayerByLayer) {
  RendererOptions options;
  options.samples = 4;
  expect_runs_equal(options, {.ground = true});
}

/// The test above cannot pass vacuously: the body moves, so consecutive frames differ.
TEST(StaticLayers, RunFramesDiffer) {
  Renderer renderer({kLayersWidth, kLayersHeight});
  const MeshId box = renderer.upload(box_mesh({0.5f, 0.4f, 0.3f}));
  const Image first = renderer.render(layered_frame(box, 1, {.ground = true}));
  const Image second = renderer.render(layered_frame(box, 2, {.ground = true}));
  EXPECT_GT(testing::mean_difference(first, second), 0.1);
}

}  // namespace
}  // namespace tumble::render
