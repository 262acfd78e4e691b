// The ImGui overlay at several frame sizes: golden images of a panel with log-axis drift plots
// and a label drawn at the text size of each frame, and the min/max decimation of long series.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "render/overlay_layout.hpp"
#include "render/renderer.hpp"
#include "render_support.hpp"

namespace tumble::render {
namespace {

/// A box over a gradient with the video overlay's panel laid out for a `width` x `height` frame.
DrawList overlay_frame(Renderer& renderer, int width, int height) {
  DrawList frame;
  frame.camera.eye = {3.0f, -4.0f, 2.5f};
  frame.style.background_top = {0.2f, 0.3f, 0.4f, 1.0f};
  frame.style.background_bottom = {0.8f, 0.6f, 0.1f, 1.0f};
  const Eigen::Affine3f pose(Eigen::AngleAxisf(0.5f, Eigen::Vector3f::UnitZ()));
  frame.meshes.push_back({renderer.upload(testing::box_mesh({0.6f, 0.4f, 0.3f})),
                          pose.matrix(),
                          {0.85f, 0.55f, 0.25f, 1.0f}});
  OverlayPanel panel;
  panel.font_px = overlay_font_px(width, height);
  const float unit = panel.font_px / kDefaultFontPx;
  panel.position_px = {10.0f * unit, 10.0f * unit};
  panel.width_px = 240.0f * unit;
  panel.title = "t-handle";
  panel.lines = {"integrator rk4, dt = 0.001 s", "t = 2.000 s of 10 s"};
  // A drift growing from 1e-15 to 1e-9 over 600 frames, and a linear one around zero.
  Plot energy{"energy drift", {}, {}, {}, 3.0f * panel.font_px, PlotAxis::kLog};
  Plot spin{"wx", {}, {}, {}, 3.0f * panel.font_px};
  for (int i = 0; i < 600; ++i) {
    energy.values.push_back(std::pow(10.0f, -15.0f + 6.0f * static_cast<float>(i) / 599.0f));
    spin.values.push_back(std::sin(0.05f * static_cast<float>(i)));
  }
  panel.plots = {energy, spin};
  frame.panels.push_back(panel);
  frame.labels.push_back({"w", Eigen::Vector3f(0.0f, 0.0f, 0.6f), {}, {1, 1, 0, 1}});
  return frame;
}

class OverlayGolden : public ::testing::TestWithParam<std::pair<int, int>> {};

TEST_P(OverlayGolden, PanelAndPlotsScaleWithTheFrame) {
  const auto [width, height] = GetParam();
  Renderer renderer({width, height, 1});
  const DrawList frame = overlay_frame(renderer, width, height);
  const Image image = renderer.render(frame);
  // The panel's background covers a point just inside its top-left corner at every size.
  const float inside = frame.panels[0].position_px.x() + 4.0f;
  DrawList bare = frame;
  bare.panels.clear();
  bare.labels.clear();
  const Image plain = renderer.render(bare);
  EXPECT_GT(
      testing::pixel_difference(image, plain, static_cast<int>(inside), static_cast<int>(inside)),
      8);
  testing::expect_matches_golden(image,
                                 "overlay_" + std::to_string(width) + "x" + std::to_string(height));
}

INSTANTIATE_TEST_SUITE_P(FrameSizes, OverlayGolden,
                         ::testing::Values(std::pair{480, 270}, std::pair{1280, 720},
                                           std::pair{3840, 2160}));

TEST(MinMaxDecimation, KeepsEveryColumnsExtremesInOrder) {
  // 1000 samples in 10 columns of 100: each column's min and max, in time order.
  std::vector<float> values(1000);
  for (std::size_t i = 0; i < values.size(); ++i) {
    values[i] = static_cast<float>((i * 37) % 101);  // a sawtooth with known extremes
  }
  const std::vector<std::size_t> kept = min_max_decimation(values, 10);
  ASSERT_EQ(kept.size(), 20u);
  for (std::size_t b = 0; b < 10; ++b) {
    const auto first = values.begin() + static_cast<long>(100 * b);
    const auto [lo, hi] = std::minmax_element(first, first + 100);
    const auto lo_i = static_cast<std::size_t>(lo - values.begin());
    const auto hi_i = static_cast<std::size_t>(hi - values.begin());
    EXPECT_EQ(kept[2 * b], std::min(lo_i, hi_i));
    EXPECT_EQ(kept[2 * b + 1], std::max(lo_i, hi_i));
  }
  // A short series is kept whole.
  EXPECT_EQ(min_max_decimation(std::vector<float>(15, 1.0f), 10).size(), 15u);
}

}  // namespace
}  // namespace tumble::render
