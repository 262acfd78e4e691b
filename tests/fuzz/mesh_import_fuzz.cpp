// Fuzz target: the whole `tumble inspect` path on a file of any bytes: engine::import_mesh
// (assimp, or tumble's binary STL reader) then engine::analyze_mesh. The first byte chooses
// the file's extension, so one target covers every format: '0' STL, '1' OBJ, '2' PLY, '3' OFF
// (the byte modulo 4); the rest is the file.
#include <array>

#include "base/errors.hpp"
#include "engine/import/mesh_import.hpp"
#include "engine/mass/mesh_analysis.hpp"
#include "fuzz_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  constexpr std::array<const char*, 4> kExtensions = {".stl", ".obj", ".ply", ".off"};
  const tumble::fuzz::TemporaryInputFile file(data + 1, size - 1, kExtensions[data[0] % 4]);
  try {
    tumble::engine::ImportStats stats;
    auto mesh = tumble::engine::import_mesh(file.path(), &stats, tumble::engine::StlReader::tumble,
                                            tumble::engine::ImportLimits{5.0, 0});
    tumble::engine::analyze_mesh(std::move(mesh), tumble::engine::MassOptions{}, "fuzz",
                                 stats.distinct_positions);
  } catch (const tumble::InputError&) {
    // A clean refusal.
  }
  return 0;
}
