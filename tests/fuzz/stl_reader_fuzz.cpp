// Fuzz target: tumble's own binary STL reader (engine/src/binary_stl.hpp) on any bytes named
// *.stl. Whatever it reads must be a mesh whose triangles index its own vertices.
#include <cstdlib>

#include "base/errors.hpp"
#include "binary_stl.hpp"
#include "fuzz_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const tumble::fuzz::TemporaryInputFile file(data, size, ".stl");
  try {
    const auto stl = tumble::engine::detail::read_binary_stl(file.path(), size);
    if (!stl) return 0;
    const auto vertices = stl->mesh.positions.size();
    for (const auto& triangle : stl->mesh.triangles) {
      for (const auto index : triangle) {
        if (index >= vertices) std::abort();  // a triangle pointing past the vertices
      }
    }
  } catch (const tumble::InputError&) {
    // A clean refusal.
  }
  return 0;
}
