// The default anti-aliasing against a 16x supersampled reference on a frame like the default
// demo's: a lit T-handle (two boxes) over the background gradient, no ground. The reference is
// the aliased frame at 4x the size per axis averaged over 4x4 blocks (16 samples a pixel); the
// error is the mean absolute difference to it over the reference's edge pixels. Aliased edges
// are off by about half the contrast on average; a filter that earns its name roughly halves
// that. No time is measured here (tests/bench/bench_antialiasing.cpp does).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <string>

#include "render/renderer.hpp"
#include "render_support.hpp"

namespace tumble::render {
namespace {

using testing::box_mesh;

constexpr int kEdgeWidth = 240;
constexpr int kEdgeHeight = 135;
constexpr int kEdgeScale = 4;  // reference samples per axis

/// The T-handle demo's body (80 x 59 x 10 mm: a bar and a stem) seen like the demo sees it,
/// tumbled by `angle` about a skew axis.
DrawList t_handle_frame(MeshId bar, MeshId stem, float angle, float line_scale) {
  DrawList frame;
  frame.camera.eye = {0.12f, -0.16f, 0.08f};
  frame.camera.target = {0.0f, 0.0f, 0.0f};
  frame.camera.near_plane = 0.01f;
  const Eigen::Affine3f pose(
      Eigen::AngleAxisf(angle, Eigen::Vector3f(0.3f, 1.0f, 0.2f).normalized()));
  const Eigen::Affine3f bar_pose = pose * Eigen::Translation3f(0.0f, 0.0195f, 0.0f);
  const Eigen::Affine3f stem_pose = pose * Eigen::Translation3f(0.0f, -0.0195f, 0.0f);
  frame.meshes.push_back({bar, bar_pose.matrix(), {0.80f, 0.55f, 0.25f, 1.0f}});
  frame.meshes.push_back({stem, stem_pose.matrix(), {0.80f, 0.55f, 0.25f, 1.0f}});
  // A trail like the demo's, at the same width in the final image whatever the render's size.
  Polyline trail;
  for (int k = 0; k <= 60; ++k) {
    const float t = 0.07f * static_cast<float>(k);
    trail.points.emplace_back(0.055f * std::cos(t), 0.03f * std::sin(t),
                              0.02f * std::sin(1.7f * t));
  }
  trail.colour = {0.95f, 0.75f, 0.2f, 1.0f};
  trail.width_px = 2.0f * line_scale;
  frame.polylines.push_back(trail);
  return frame;
}

Image render_t_handle(RendererOptions options, float angle) {
  Renderer renderer(options);
  const MeshId bar = renderer.upload(box_mesh({0.04f, 0.01f, 0.005f}));
  const MeshId stem = renderer.upload(box_mesh({0.005f, 0.0295f - 0.01f, 0.005f}));
  return renderer.render(
      t_handle_frame(bar, stem, angle, static_cast<float>(options.width) / kEdgeWidth));
}

/// Mean absolute difference (0..255 a channel) to the block means of `big` over the pixels
/// whose block is not uniform (an edge crosses them).
double edge_error_to_reference(const Image& image, const Image& big) {
  double sum = 0.0;
  int count = 0;
  for (int y = 0; y < kEdgeHeight; ++y) {
    for (int x = 0; x < kEdgeWidth; ++x) {
      for (int c = 0; c < 3; ++c) {
        int lo = 255;
        int hi = 0;
        double mean = 0.0;
        for (int j = 0; j < kEdgeScale; ++j) {
          for (int i = 0; i < kEdgeScale; ++i) {
            const int v = big.pixel(x * kEdgeScale + i, y * kEdgeScale + j)[c];
            lo = std::min(lo, v);
            hi = std::max(hi, v);
            mean += v;
          }
        }
        if (hi - lo <= 8) continue;
        mean /= kEdgeScale * kEdgeScale;
        sum += std::abs(static_cast<double>(image.pixel(x, y)[c]) - mean);
        ++count;
      }
    }
  }
  EXPECT_GT(count, 300) << "the frame has edges to measure";
  return count > 0 ? sum / count : 0.0;
}

TEST(AntialiasingEdges, DefaultFilterCutsTheTHandlesEdgeErrorByAThird) {
  for (const float angle : {0.3f, 1.1f, 2.0f}) {
    const Image big = render_t_handle({kEdgeWidth * kEdgeScale, kEdgeHeight * kEdgeScale}, angle);
    const double aliased =
        edge_error_to_reference(render_t_handle({kEdgeWidth, kEdgeHeight}, angle), big);
    RendererOptions fxaa{kEdgeWidth, kEdgeHeight};
    fxaa.filter = AntialiasingFilter::fxaa;
    const double filtered = edge_error_to_reference(render_t_handle(fxaa, angle), big);
    RecordProperty("aliased_error", std::to_string(aliased));
    RecordProperty("filtered_error", std::to_string(filtered));
    EXPECT_GT(aliased, 10.0);  // hard edges to smooth
    EXPECT_LE(filtered, 0.7 * aliased) << "angle " << angle;
  }
}

}  // namespace
}  // namespace tumble::render
