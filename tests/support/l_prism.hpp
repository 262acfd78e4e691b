#pragma once
// The L-shaped prism the inertia-method tests share: concave, closed and consistently wound, so
// exact, convex (hull) and MuJoCo's legacy method all give different answers on it.

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "engine/geometry/triangle_mesh.hpp"

namespace tumble::testing {

/// The prism over the L (0,0) (2,0) (2,1) (1,1) (1,2) (0,2), z from 0 to 1, caps fanned from
/// the first corner: volume 3, its convex hull's 3.5.
inline engine::TriangleMesh l_prism() {
  const std::vector<Eigen::Vector2d> outline = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  engine::TriangleMesh mesh;
  const auto n = static_cast<std::uint32_t>(outline.size());
  for (double z : {0.0, 1.0}) {
    for (const Eigen::Vector2d& p : outline) mesh.positions.emplace_back(p.x(), p.y(), z);
  }
  for (std::uint32_t i = 1; i + 1 < n; ++i) {
    mesh.triangles.push_back({0, i + 1, i});
    mesh.triangles.push_back({n, n + i, n + i + 1});
  }
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t j = (i + 1) % n;
    mesh.triangles.push_back({i, j, n + j});
    mesh.triangles.push_back({i, n + j, n + i});
  }
  return mesh;
}

}  // namespace tumble::testing
