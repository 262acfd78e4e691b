#pragma once
// Writes a triangle mesh as binary STL (test and benchmark fixtures).

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "engine/triangle_mesh.hpp"

namespace tumble::testing {

inline void write_binary_stl(const std::filesystem::path& file, const engine::TriangleMesh& mesh) {
  std::ofstream out(file, std::ios::binary);
  const char header[80] = "binary STL written by tumble's test support";
  out.write(header, sizeof header);
  const auto count = static_cast<std::uint32_t>(mesh.triangles.size());
  out.write(reinterpret_cast<const char*>(&count), sizeof count);
  for (const auto& t : mesh.triangles) {
    float record[12] = {};  // normal (left zero: readers recompute it), then three corners
    for (int corner = 0; corner < 3; ++corner) {
      for (int axis = 0; axis < 3; ++axis) {
        record[3 + 3 * corner + axis] = static_cast<float>(mesh.positions[t[corner]][axis]);
      }
    }
    out.write(reinterpret_cast<const char*>(record), sizeof record);
    const std::uint16_t attributes = 0;
    out.write(reinterpret_cast<const char*>(&attributes), sizeof attributes);
  }
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

}  // namespace tumble::testing
