#pragma once
/// @file An indexed triangle mesh: the only geometry the engine needs.

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace tumble::engine {

/// Indexed triangles with counter-clockwise winding seen from outside (outward normals).
struct TriangleMesh {
  std::vector<Eigen::Vector3d> positions;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

}  // namespace tumble::engine
