#pragma once
// Robot-file test fixtures: box meshes placed by hand, and files written into a test folder.

#include <filesystem>
#include <fstream>
#include <string>

#include <Eigen/Geometry>

#include "support/stl_writer.hpp"

namespace tumble::testing {

/// An ASCII STL of the box of `size` centred at `center`, each corner then mapped by
/// `transform` (a mirroring transform reverses the winding, so that the solid stays
/// outward-wound).
inline std::string placed_box_stl(const Eigen::Vector3d& size, const Eigen::Vector3d& center,
                                  const Eigen::Affine3d& transform = Eigen::Affine3d::Identity()) {
  const auto corner = [&](int i) {
    const Eigen::Vector3d unit((i & 1) - 0.5, ((i >> 1) & 1) - 0.5, ((i >> 2) & 1) - 0.5);
    return Eigen::Vector3d(transform * (center + unit.cwiseProduct(size)));
  };
  const bool mirrored = transform.linear().determinant() < 0.0;
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  return ascii_stl_solid("box", 12, [&](std::size_t i) {
    const int* q = quads[i / 2];
    const int second = i % 2 == 0 ? 1 : 2;
    const Eigen::Vector3d a = corner(q[0]), b = corner(q[second]), c = corner(q[second + 1]);
    return mirrored ? StlTriangle{Eigen::Vector3d::Zero(), a, c, b}
                    : StlTriangle{Eigen::Vector3d::Zero(), a, b, c};
  });
}

/// Writes `text` to `file` verbatim.
inline void write_file(const std::filesystem::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out << text;
}

}  // namespace tumble::testing
