// The FXAA post-process against an oracle: the true pixel coverage of a dark box on a light
// background, from an aliased render at 4x the size averaged over 4x4 blocks.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdlib>

#include "render/renderer.hpp"
#include "render_support.hpp"

namespace tumble::render {
namespace {

using testing::box_mesh;

constexpr int kAaWidth = 160;
constexpr int kAaHeight = 120;
constexpr int kScale = 4;  // oracle supersampling per axis

DrawList box_frame(MeshId box) {
  DrawList frame;
  frame.camera.eye = {3.0f, -4.0f, 2.5f};
  frame.camera.target = {0.0f, 0.0f, 0.0f};
  frame.camera.up = Eigen::Vector3f::UnitZ();
  frame.style.background_top = {0.92f, 0.92f, 0.9f, 1.0f};
  frame.style.background_bottom = {0.85f, 0.86f, 0.88f, 1.0f};
  const Eigen::Affine3f pose(Eigen::AngleAxisf(0.4f, Eigen::Vector3f::UnitZ()) *
                             Eigen::AngleAxisf(0.25f, Eigen::Vector3f::UnitX()));
  frame.meshes.push_back({box, pose.matrix(), {0.08f, 0.08f, 0.1f, 1.0f}});
  return frame;
}

Image render_box(const RendererOptions& options) {
  Renderer renderer(options);
  return renderer.render(box_frame(renderer.upload(box_mesh({1.0f, 0.8f, 0.6f}))));
}

/// The oracle: each pixel the mean of its kScale x kScale sub-pixels (in 0..255).
struct Oracle {
  std::vector<float> mean;    // 3 channels a pixel
  std::vector<bool> partial;  // the block is not uniform: an edge crosses the pixel
};

Oracle box_oracle() {
  const Image big = render_box({kAaWidth * kScale, kAaHeight * kScale});
  Oracle oracle{std::vector<float>(3 * kAaWidth * kAaHeight, 0.0f),
                std::vector<bool>(kAaWidth * kAaHeight, false)};
  for (int y = 0; y < kAaHeight; ++y) {
    for (int x = 0; x < kAaWidth; ++x) {
      for (int c = 0; c < 3; ++c) {
        int lo = 255;
        int hi = 0;
        float sum = 0.0f;
        for (int j = 0; j < kScale; ++j) {
          for (int i = 0; i < kScale; ++i) {
            const int v = big.rgba[4 * ((y * kScale + j) * big.width + x * kScale + i) + c];
            lo = std::min(lo, v);
            hi = std::max(hi, v);
            sum += static_cast<float>(v);
          }
        }
        oracle.mean[3 * (y * kAaWidth + x) + c] = sum / (kScale * kScale);
        if (hi - lo > 8) oracle.partial[y * kAaWidth + x] = true;
      }
    }
  }
  return oracle;
}

/// Mean absolute difference to the oracle (0..255 a channel) over the oracle's edge pixels.
double edge_error(const Image& image, const Oracle& oracle) {
  double sum = 0.0;
  int count = 0;
  for (int p = 0; p < kAaWidth * kAaHeight; ++p) {
    if (!oracle.partial[p]) continue;
    for (int c = 0; c < 3; ++c) {
      sum += std::abs(static_cast<float>(image.rgba[4 * p + c]) - oracle.mean[3 * p + c]);
      ++count;
    }
  }
  return count > 0 ? sum / count : 0.0;
}

RendererOptions fxaa_options() {
  RendererOptions options{kAaWidth, kAaHeight};
  options.filter = AntialiasingFilter::fxaa;
  return options;
}

TEST(Antialiasing, FxaaIsOffByDefaultAndOnWhenAsked) {
  EXPECT_EQ(Renderer({kAaWidth, kAaHeight}).filter(), AntialiasingFilter::none);
  EXPECT_EQ(Renderer(fxaa_options()).filter(), AntialiasingFilter::fxaa);
  RendererOptions both = fxaa_options();
  both.samples = 4;  // multisampling wins: the filter would only blur resolved edges
  EXPECT_EQ(Renderer(both).filter(), AntialiasingFilter::none);
}

TEST(Antialiasing, FxaaEdgesAreCloserToTheTrueCoverage) {
  const Oracle oracle = box_oracle();
  const double aliased = edge_error(render_box({kAaWidth, kAaHeight}), oracle);
  const double filtered = edge_error(render_box(fxaa_options()), oracle);
  RecordProperty("aliased_error", std::to_string(aliased));
  RecordProperty("fxaa_error", std::to_string(filtered));
  EXPECT_GT(aliased, 20.0);  // the scene has hard, high-contrast edges to smooth
  EXPECT_LE(filtered, 0.6 * aliased) << "aliased " << aliased << ", fxaa " << filtered;
}

TEST(Antialiasing, FlatRegionsAreUnchanged) {
  const Oracle oracle = box_oracle();
  const Image aliased = render_box({kAaWidth, kAaHeight});
  const Image filtered = render_box(fxaa_options());
  int far = 0;
  for (int y = 3; y < kAaHeight - 3; ++y) {
    for (int x = 3; x < kAaWidth - 3; ++x) {
      bool near_edge = false;
      for (int j = -3; j <= 3 && !near_edge; ++j) {
        for (int i = -3; i <= 3 && !near_edge; ++i) {
          near_edge = oracle.partial[(y + j) * kAaWidth + x + i];
        }
      }
      if (near_edge) continue;
      ++far;
      EXPECT_LE(testing::pixel_difference(aliased, filtered, x, y), 1) << x << "," << y;
    }
  }
  EXPECT_GT(far, kAaWidth * kAaHeight / 2);
}

TEST(Antialiasing, OverlayTextIsNotFiltered) {
  DrawList frame;  // the gradient alone: no scene edge, so only the overlay could differ
  frame.style.background_top = {0.2f, 0.3f, 0.4f, 1.0f};
  frame.style.background_bottom = {0.8f, 0.6f, 0.1f, 1.0f};
  OverlayPanel panel;
  panel.title = "t-handle";
  panel.position_px = {4.0f, 4.0f};
  panel.width_px = 90.0f;
  panel.lines = {"t = 1.25 s"};
  frame.panels.push_back(panel);
  frame.labels.push_back({"HELLO", std::nullopt, {100.0f, 80.0f}, {1, 1, 1, 1}});
  Renderer aliased({kAaWidth, kAaHeight});
  Renderer filtered(fxaa_options());
  const Image a = aliased.render(frame);
  const Image b = filtered.render(frame);
  ASSERT_EQ(a.rgba.size(), b.rgba.size());
  int text_pixels = 0;  // the text is there, with hard edges the filter would have softened
  for (int y = 0; y < kAaHeight; ++y) {
    for (int x = 0; x < kAaWidth; ++x) {
      EXPECT_EQ(testing::pixel_difference(a, b, x, y), 0) << x << "," << y;
      if (y + 1 < kAaHeight && std::abs(a.pixel(x, y)[0] - a.pixel(x, y + 1)[0]) > 60) {
        ++text_pixels;
      }
    }
  }
  EXPECT_GT(text_pixels, 20);
}

}  // namespace
}  // namespace tumble::render
