#pragma once
// Box meshes written as files for tests and benchmarks of `tumble inspect`: a box of any size,
// rotation and centre, as exact ASCII STL, binary STL, OBJ or ASCII PLY, and its closed-form
// inertia.

#include <Eigen/Core>
#include <array>
#include <filesystem>
#include <fstream>
#include <string>

#include "support/stl_writer.hpp"

namespace tumble::testing {

/// A box of edge lengths `size`, turned by `rotation` and centred at `centre`: its 8 corners
/// (bit 0 = +x half, bit 1 = +y, bit 2 = +z) and 6 outward-wound quads.
struct BoxMesh {
  std::array<Eigen::Vector3d, 8> corners;
  static constexpr int kQuads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                       {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};

  BoxMesh(const Eigen::Vector3d& size,
          const Eigen::Matrix3d& rotation = Eigen::Matrix3d::Identity(),
          const Eigen::Vector3d& centre = Eigen::Vector3d::Zero()) {
    for (int i = 0; i < 8; ++i) {
      const Eigen::Vector3d half((i & 1 ? 0.5 : -0.5) * size.x(), (i & 2 ? 0.5 : -0.5) * size.y(),
                                 (i & 4 ? 0.5 : -0.5) * size.z());
      corners[i] = rotation * half + centre;
    }
  }

  /// Triangle `i` of 12 (two per quad), as the STL writers take it.
  StlTriangle triangle(std::size_t i) const {
    const int* q = kQuads[i / 2];
    const int second = i % 2 == 0 ? 1 : 2;
    return {Eigen::Vector3d::Zero(), corners[q[0]], corners[q[second]], corners[q[second + 1]]};
  }
};

/// ASCII STL, every coordinate written to read back exactly.
inline void write_box_ascii_stl(const std::filesystem::path& file, const BoxMesh& box) {
  write_stl_file(file, ascii_stl_solid("box", 12, [&](std::size_t i) { return box.triangle(i); }));
}

/// Binary STL (float32 coordinates).
inline void write_box_binary_stl(const std::filesystem::path& file, const BoxMesh& box) {
  write_stl_file(file, binary_stl_bytes(
                           12, [&](std::size_t i) { return box.triangle(i); }, "box"));
}

/// Wavefront OBJ with quads, coordinates to 17 digits.
inline void write_box_obj(const std::filesystem::path& file, const BoxMesh& box) {
  std::ofstream out(file);
  out.precision(17);
  for (const Eigen::Vector3d& c : box.corners)
    out << "v " << c.x() << " " << c.y() << " " << c.z() << "\n";
  for (const auto& q : BoxMesh::kQuads) {
    out << "f " << q[0] + 1 << " " << q[1] + 1 << " " << q[2] + 1 << " " << q[3] + 1 << "\n";
  }
}

/// ASCII PLY with quads.
inline void write_box_ply(const std::filesystem::path& file, const BoxMesh& box) {
  std::ofstream out(file);
  out.precision(17);
  out << "ply\nformat ascii 1.0\nelement vertex 8\nproperty double x\nproperty double y\n"
         "property double z\nelement face 6\nproperty list uchar int vertex_indices\n"
         "end_header\n";
  for (const Eigen::Vector3d& c : box.corners) out << c.x() << " " << c.y() << " " << c.z() << "\n";
  for (const auto& q : BoxMesh::kQuads) {
    out << "4 " << q[0] << " " << q[1] << " " << q[2] << " " << q[3] << "\n";
  }
}

/// The inertia of a uniform box of edge lengths `size` and mass `mass` about its centre in its
/// own axes: m (b^2 + c^2) / 12 and so on.
inline Eigen::Vector3d box_moments(double mass, const Eigen::Vector3d& size) {
  const Eigen::Vector3d s2 = size.cwiseProduct(size);
  return mass / 12.0 * Eigen::Vector3d(s2.y() + s2.z(), s2.x() + s2.z(), s2.x() + s2.y());
}

}  // namespace tumble::testing
