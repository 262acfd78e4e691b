#pragma once
// Shared helpers of the render tests: simple meshes, an independent pinhole projection,
// image comparisons and golden images (regenerate with TUMBLE_UPDATE_GOLDEN=1).

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include "base/image.hpp"
#include "media/png_io.hpp"
#include "render/draw_list.hpp"
#include "support/image_compare.hpp"

namespace tumble::render::testing {

using tumble::testing::mean_difference;

/// The solids of the frame-by-frame comparison runs: `box` tumbled by `angle` at `centre`
/// (opaque), a translucent copy of it and a green arrow.
inline void add_run_solids(DrawList& frame, MeshId box, const Eigen::Vector3f& centre,
                           float angle) {
  const Eigen::Affine3f pose =
      Eigen::Translation3f(centre) *
      Eigen::AngleAxisf(angle, Eigen::Vector3f(0.3f, 0.5f, 0.8f).normalized());
  frame.meshes.push_back({box, pose.matrix(), {0.8f, 0.3f, 0.2f, 1.0f}});
  const Eigen::Affine3f glass = Eigen::Translation3f(-1.2f, 0.8f, 0.0f) * Eigen::Scaling(0.6f);
  frame.meshes.push_back({box, glass.matrix(), {0.2f, 0.5f, 0.9f, 0.5f}});
  frame.arrows.push_back({{0.0f, 0.0f, 0.2f}, {0.0f, 0.0f, 1.2f}, {0.2f, 0.8f, 0.3f, 1.0f}});
}

/// Box with the given half extents, 8 vertices, 12 outward triangles (flat shaded).
inline MeshData box_mesh(const Eigen::Vector3f& half) {
  MeshData mesh;
  for (int i = 0; i < 8; ++i) {
    mesh.positions.emplace_back((i & 1 ? 1.0f : -1.0f) * half.x(),
                                (i & 2 ? 1.0f : -1.0f) * half.y(),
                                (i & 4 ? 1.0f : -1.0f) * half.z());
  }
  mesh.indices = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                  2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
  return mesh;
}

/// Pinhole projection written independently of render/camera_math: camera basis vectors and a
/// focal length in pixels. Returns pixel coordinates (y down).
inline Eigen::Vector2f pinhole_project(const Camera& camera, int width, int height,
                                       const Eigen::Vector3f& world) {
  const Eigen::Vector3f forward = (camera.target - camera.eye).normalized();
  const Eigen::Vector3f right = forward.cross(camera.up).normalized();
  const Eigen::Vector3f up = right.cross(forward);
  const Eigen::Vector3f d = world - camera.eye;
  const float focal_px = 0.5f * static_cast<float>(height) /
                         std::tan(0.5f * camera.vertical_fov_deg * std::numbers::pi_v<float> / 180);
  const float depth = d.dot(forward);
  return {0.5f * static_cast<float>(width) + focal_px * d.dot(right) / depth,
          0.5f * static_cast<float>(height) - focal_px * d.dot(up) / depth};
}

/// Convex hull (counter-clockwise in y-down pixel space is irrelevant: we use signed distances).
inline std::vector<Eigen::Vector2f> convex_hull(std::vector<Eigen::Vector2f> p) {
  std::sort(p.begin(), p.end(), [](const auto& a, const auto& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  auto cross = [](const Eigen::Vector2f& o, const Eigen::Vector2f& a, const Eigen::Vector2f& b) {
    return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
  };
  std::vector<Eigen::Vector2f> hull(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
    hull[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross(hull[k - 2], hull[k - 1], p[i - 1]) <= 0) --k;
    hull[k++] = p[i - 1];
  }
  hull.resize(k - 1);
  return hull;
}

/// Signed distance (pixels) from a point to a convex polygon's boundary: > 0 inside.
inline float inside_distance(const std::vector<Eigen::Vector2f>& hull, const Eigen::Vector2f& q) {
  float distance = 1e30f;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Eigen::Vector2f a = hull[i];
    const Eigen::Vector2f b = hull[(i + 1) % hull.size()];
    const Eigen::Vector2f edge = (b - a).normalized();
    const Eigen::Vector2f normal(-edge.y(), edge.x());  // left of a->b, inside for this winding
    distance = std::min(distance, normal.dot(q - a));
  }
  return distance;
}

/// Expected 8-bit background value of row y for the vertical gradient.
inline float gradient_value(float top, float bottom, int y, int height) {
  const float t = (static_cast<float>(y) + 0.5f) / static_cast<float>(height);
  return 255.0f * (top + (bottom - top) * t);
}

/// Largest channel difference of pixel (x, y) between two images.
inline int pixel_difference(const Image& a, const Image& b, int x, int y) {
  int worst = 0;
  for (int c = 0; c < 3; ++c)
    worst = std::max(worst, std::abs(a.pixel(x, y)[c] - b.pixel(x, y)[c]));
  return worst;
}

/// Compares with tests/render/golden/<name>.png: at most 1 % of pixels may differ by more than
/// 32 levels in a channel and the mean difference must stay under 1.5 levels. With
/// TUMBLE_UPDATE_GOLDEN=1 the golden is rewritten instead.
inline void expect_matches_golden(const Image& image, const std::string& name) {
  const std::filesystem::path golden =
      std::filesystem::path(TUMBLE_SOURCE_DIR) / "tests/render/golden" / (name + ".png");
  const char* update = std::getenv("TUMBLE_UPDATE_GOLDEN");
  if (update != nullptr && std::string(update) == "1") {
    media::write_png(golden, image, 9);
    GTEST_SKIP() << "rewrote " << golden;
  }
  ASSERT_TRUE(std::filesystem::exists(golden))
      << golden << " missing: run with TUMBLE_UPDATE_GOLDEN=1";
  const Image expected = media::read_png(golden);
  ASSERT_EQ(expected.width, image.width);
  ASSERT_EQ(expected.height, image.height);
  EXPECT_LE(tumble::testing::pixels_differing(expected, image, 32),
            static_cast<std::size_t>(image.width * image.height / 100))
      << name;
  EXPECT_LT(mean_difference(expected, image), 1.5) << name;
}

}  // namespace tumble::render::testing
