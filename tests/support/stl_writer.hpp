#pragma once
// Binary and ASCII STL bytes and files (test and benchmark fixtures).

#include <array>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "engine/geometry/triangle_mesh.hpp"

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

/// One `solid NAME ... endsolid NAME` block of an ASCII STL of `count` triangles,
/// `triangle(i)` giving each (normal, then corners), every number as printf("%.17g") writes it
/// (reads back as the same double).
template <typename TriangleAt>
std::string ascii_stl_solid(const std::string& name, std::size_t count, TriangleAt triangle) {
  const auto append = [](std::string& text, const Eigen::Vector3d& v) {
    for (int axis = 0; axis < 3; ++axis) {
      char buffer[32];
      const auto end =
          std::to_chars(buffer, buffer + sizeof buffer, v[axis], std::chars_format::general, 17)
              .ptr;
      text.append(" ").append(buffer, end);
    }
    text += "\n";
  };
  std::string text = "solid " + name + "\n";
  for (std::size_t i = 0; i < count; ++i) {
    const StlTriangle t = triangle(i);
    text += "  facet normal";
    append(text, t[0]);
    text += "    outer loop\n";
    for (int corner = 1; corner <= 3; ++corner) {
      text += "      vertex";
      append(text, t[corner]);
    }
    text += "    endloop\n  endfacet\n";
  }
  return text + "endsolid " + name + "\n";
}

/// Writes `bytes` (binary or text) to `file` verbatim.
inline void write_stl_file(const std::filesystem::path& file, const std::string& bytes) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw std::runtime_error("cannot write " + file.string());
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
  write_stl_file(file, bytes);
}

}  // namespace tumble::testing
