#pragma once
// Binary STL bytes and files (test and benchmark fixtures).

#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "engine/triangle_mesh.hpp"

namespace tumble::testing {

/// One triangle as binary STL stores it: a normal (zero lets readers work it out), then the
/// three corners.
using StlTriangle = std::array<Eigen::Vector3d, 4>;

/// The bytes of a binary STL of `count` triangles, `triangle(i)` giving each: an 80-byte
/// header (`header`, cut or padded with zeros), the count, then per triangle twelve
/// little-endian float32 values and a zero attribute word.
template <typename TriangleAt>
std::string binary_stl_bytes(std::size_t count, TriangleAt triangle, std::string header) {
  const auto append = [](std::string& bytes, const auto value) {
    char raw[sizeof value];
    std::memcpy(raw, &value, sizeof value);
    bytes.append(raw, sizeof value);
  };
  header.resize(80, '\0');
  std::string bytes = std::move(header);
  bytes.reserve(84 + 50 * count);
  append(bytes, static_cast<std::uint32_t>(count));
  for (std::size_t i = 0; i < count; ++i) {
    for (const Eigen::Vector3d& v : static_cast<StlTriangle>(triangle(i))) {
      for (int axis = 0; axis < 3; ++axis) append(bytes, static_cast<float>(v[axis]));
    }
    append(bytes, std::uint16_t{0});
  }
  return bytes;
}

/// Writes `mesh` as binary STL (zero normals).
inline void write_binary_stl(const std::filesystem::path& file, const engine::TriangleMesh& mesh) {
  const std::string bytes = binary_stl_bytes(
      mesh.triangles.size(),
      [&](std::size_t i) {
        const auto& t = mesh.triangles[i];
        return StlTriangle{Eigen::Vector3d::Zero(), mesh.positions[t[0]], mesh.positions[t[1]],
                           mesh.positions[t[2]]};
      },
      "binary STL written by tumble's test support");
  std::ofstream out(file, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

}  // namespace tumble::testing
