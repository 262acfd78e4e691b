#pragma once
// A torus about z as the renderer takes it (smooth normals, indexed): the render tests' and
// benchmarks' body of any triangle count, with a closed-form surface to check against.

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "render/draw_list.hpp"

namespace tumble::testing {

/// Torus of radii `major` (the tube's centre) and `minor` (the tube): 2 * rings * sides
/// triangles, each vertex with its exact unit normal.
inline render::MeshData torus_mesh(int rings, int sides, float major = 0.6f, float minor = 0.25f) {
  render::MeshData mesh;
  const float two_pi = 2.0f * std::numbers::pi_v<float>;
  for (int i = 0; i < rings; ++i) {
    const float u = two_pi * static_cast<float>(i) / static_cast<float>(rings);
    for (int j = 0; j < sides; ++j) {
      const float v = two_pi * static_cast<float>(j) / static_cast<float>(sides);
      const Eigen::Vector3f centre(major * std::cos(u), major * std::sin(u), 0.0f);
      const Eigen::Vector3f normal(std::cos(v) * std::cos(u), std::cos(v) * std::sin(u),
                                   std::sin(v));
      mesh.positions.push_back(centre + minor * normal);
      mesh.normals.push_back(normal);
    }
  }
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < sides; ++j) {
      const auto a = static_cast<std::uint32_t>(i * sides + j);
      const auto b = static_cast<std::uint32_t>(((i + 1) % rings) * sides + j);
      const auto c = static_cast<std::uint32_t>(((i + 1) % rings) * sides + (j + 1) % sides);
      const auto d = static_cast<std::uint32_t>(i * sides + (j + 1) % sides);
      mesh.indices.insert(mesh.indices.end(), {a, b, c, a, c, d});
    }
  }
  return mesh;
}

}  // namespace tumble::testing
