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

/// Frame `i` of a run: a box tumbling over the ground (when `ground`), a translucent box, an
/// arrow, a trail, points and a label; the camera moves from frame 6 on and the background
/// changes at frame 9. `jumping`: the box jumps from side to side and there is no trail, so the
/// drawn box moves and shrinks as well as grows.
DrawList layered_frame(MeshId box, int i, bool ground, bool label = true, bool jumping = false) {
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
  if (label) {
    Label text;
    text.text = "frame " + std::to_string(i);
    text.screen_px = {8.0f, 8.0f};
    frame.labels.push_back(text);
  }
  return frame;
}

/// Renders the run twice, with and without stored layers, and compares every frame.
void expect_runs_equal(RendererOptions options, bool ground, bool label = true,
                       bool jumping = false) {
  options.width = kLayersWidth;
  options.height = kLayersHeight;
  RendererOptions drawn_options = options;
  drawn_options.reuse_static_layers = false;
  Renderer reused(options);
  Renderer drawn(drawn_options);
  const MeshId reused_box = reused.upload(box_mesh({0.5f, 0.4f, 0.3f}));
  const MeshId drawn_box = drawn.upload(box_mesh({0.5f, 0.4f, 0.3f}));
  for (int i = 0; i < 12; ++i) {
    if (i == 10) {  // a new size, then back: the stored copy is made again
      reused.resize(kLayersWidth + 20, kLayersHeight);
      reused.resize(kLayersWidth, kLayersHeight);
    }
    const Image a = reused.render(layered_frame(reused_box, i, ground, label, jumping));
    const Image b = drawn.render(layered_frame(drawn_box, i, ground, label, jumping));
    ASSERT_EQ(a.width, b.width);
    ASSERT_EQ(a.height, b.height);
    std::size_t differing = 0;
    for (std::size_t k = 0; k < a.rgba.size(); ++k) differing += a.rgba[k] != b.rgba[k];
    EXPECT_EQ(differing, 0u) << "frame " << i;
  }
}

TEST(StaticLayers, GroundAndShadowFramesEqualThoseDrawnLayerByLayer) {
  expect_runs_equal(RendererOptions{}, /*ground=*/true);
}

TEST(StaticLayers, BackgroundOnlyFramesEqualThoseDrawnLayerByLayer) {
  expect_runs_equal(RendererOptions{}, /*ground=*/false);
}

// Without a ground, a frame restores only the box the last one drew in: with the overlay drawn
// into the scene's framebuffer (no filter), after the filter, and with nothing but the scene.
TEST(StaticLayers, BackgroundOnlyFramesRestoringTheLastDrawnBoxEqualThoseDrawnLayerByLayer) {
  RendererOptions filtered;
  filtered.filter = AntialiasingFilter::fxaa;
  expect_runs_equal(filtered, /*ground=*/false);
  expect_runs_equal(RendererOptions{}, /*ground=*/false, /*label=*/false);
  expect_runs_equal(filtered, /*ground=*/false, /*label=*/false);
  for (const bool label : {false, true}) {
    expect_runs_equal(RendererOptions{}, /*ground=*/false, label, /*jumping=*/true);
    expect_runs_equal(filtered, /*ground=*/false, label, /*jumping=*/true);
  }
}

TEST(StaticLayers, FilteredFramesEqualThoseDrawnLayerByLayer) {
  RendererOptions options;
  options.filter = AntialiasingFilter::fxaa;
  expect_runs_equal(options, /*ground=*/true);
}

TEST(StaticLayers, MultisampledFramesEqualThoseDrawnLayerByLayer) {
  RendererOptions options;
  options.samples = 4;
  expect_runs_equal(options, /*ground=*/true);
}

/// The test above cannot pass vacuously: the body moves, so consecutive frames differ.
TEST(StaticLayers, RunFramesDiffer) {
  Renderer renderer({kLayersWidth, kLayersHeight});
  const MeshId box = renderer.upload(box_mesh({0.5f, 0.4f, 0.3f}));
  const Image first = renderer.render(layered_frame(box, 1, true));
  const Image second = renderer.render(layered_frame(box, 2, true));
  EXPECT_GT(testing::mean_difference(first, second), 0.1);
}

}  // namespace
}  // namespace tumble::render
