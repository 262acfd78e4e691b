// Simplified copies with meshoptimizer's edge-collapse simplifier (meshopt_simplify: quadric
// error metrics after Garland & Heckbert, "Surface Simplification Using Quadric Error Metrics",
// SIGGRAPH 1997), which keeps a subset of the original vertices, so every level shares the
// full mesh's vertex buffer and normals.
//
// Error bound. meshopt_simplify reports its quadric error (Garland & Heckbert): the distance of
// the kept vertices from the planes of the triangles they replaced, relative to the mesh's
// extent (times meshopt_simplifyScale for mesh units); summed over the chain's steps (each level
// is simplified from the one before: triangle inequality). That figure misses what matters most
// for an outline on a smooth surface: every kept vertex is an original vertex, on the surface,
// while a long new triangle's interior cuts inside a curved surface. Against the analytic torus
// the test samples, its centroids lay up to 3x deeper than the quadric figure. So each level's
// error is also measured: the largest distance of a triangle's centroid and edge midpoints from
// the tangent planes at its corners (the vertex normals). On a sphere of radius R a triangle
// whose corners are a apart sags by about a^2 / (8R) at an edge midpoint, which is the
// midpoint's distance from the corner's tangent plane, and by about twice less than that plane
// distance at the centroid, so the measure bounds the sag. The level's error is the larger of
// the two; a silhouette point moves by at most it, hence by error * pixels-per-unit pixels.
#include "mesh_lod.hpp"

#include <meshoptimizer.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace tumble::render::detail {

namespace {

/// Stop when a level would have fewer triangles than this, or shrank by less than a tenth.
constexpr std::size_t kCoarsestTriangles = 2000;
constexpr double kLeastShrink = 0.9;
/// The first simplified copy has a quarter of the triangles, and at least this many.
constexpr std::size_t kFirstTriangles = 10000;

}  // namespace

float interior_deviation(const std::vector<Eigen::Vector3f>& positions,
                         const std::vector<Eigen::Vector3f>& normals, const std::uint32_t* indices,
                         std::size_t count) {
  float worst = 0.0f;
  for (std::size_t t = 0; t + 2 < count; t += 3) {
    const Eigen::Vector3f* p[3] = {&positions[indices[t]], &positions[indices[t + 1]],
                                   &positions[indices[t + 2]]};
    const Eigen::Vector3f* n[3] = {&normals[indices[t]], &normals[indices[t + 1]],
                                   &normals[indices[t + 2]]};
    const Eigen::Vector3f centroid = (*p[0] + *p[1] + *p[2]) / 3.0f;
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3f& corner = *p[i];
      const Eigen::Vector3f& normal = *n[i];
      const Eigen::Vector3f next = 0.5f * (corner + *p[(i + 1) % 3]);
      const Eigen::Vector3f previous = 0.5f * (corner + *p[(i + 2) % 3]);
      worst =
          std::max({worst, std::abs(normal.dot(centroid - corner)),
                    std::abs(normal.dot(next - corner)), std::abs(normal.dot(previous - corner))});
    }
  }
  return worst;
}

std::vector<LodLevel> build_lod_chain(const std::vector<Eigen::Vector3f>& positions,
                                      const std::vector<Eigen::Vector3f>& normals,
                                      const std::vector<std::uint32_t>& full,
                                      std::vector<std::uint32_t>& indices) {
  indices.assign(full.begin(), full.end());
  std::vector<LodLevel> levels{{0, full.size(), 0.0f}};
  if (full.size() / 3 <= kLodMinTriangles || positions.empty() ||
      normals.size() != positions.size()) {
    return levels;
  }

  const float* xyz = positions.front().data();
  const std::size_t stride = sizeof(Eigen::Vector3f);
  static_assert(sizeof(Eigen::Vector3f) == 3 * sizeof(float), "packed positions");
  const float scale = meshopt_simplifyScale(xyz, positions.size(), stride);
  std::vector<std::uint32_t> previous(full.begin(), full.end());
  std::vector<std::uint32_t> next(full.size());
  float error = 0.0f;
  // The first copy is made from the full mesh straight down to a quarter (one pass over the
  // big mesh: each simplification costs about as much as its input, so halving from a million
  // triangles would cost twice this), the others halve the one before.
  std::size_t target = std::max(full.size() / 3 / 4, kFirstTriangles) * 3;
  while (target / 3 >= kCoarsestTriangles && target < previous.size()) {
    float step_error = 0.0f;
    const std::size_t made =
        meshopt_simplify(next.data(), previous.data(), previous.size(), xyz, positions.size(),
                         stride, target, std::numeric_limits<float>::max(), 0, &step_error);
    if (made == 0 ||
        static_cast<double>(made) > kLeastShrink * static_cast<double>(previous.size())) {
      break;
    }
    error += step_error * scale;
    const float measured = interior_deviation(positions, normals, next.data(), made);
    levels.push_back({indices.size(), made, std::max({error, measured, levels.back().error})});
    indices.insert(indices.end(), next.begin(), next.begin() + static_cast<std::ptrdiff_t>(made));
    previous.assign(next.begin(), next.begin() + static_cast<std::ptrdiff_t>(made));
    target = (made / 3 / 2) * 3;
  }
  return levels;
}

std::size_t pick_lod_level(const std::vector<LodLevel>& levels, float pixels_per_unit,
                           float max_error_px) {
  if (!(pixels_per_unit > 0.0f) || !std::isfinite(pixels_per_unit)) return 0;
  std::size_t chosen = 0;
  for (std::size_t i = 1; i < levels.size(); ++i) {
    if (levels[i].error * pixels_per_unit < max_error_px) chosen = i;
  }
  return chosen;
}

}  // namespace tumble::render::detail
