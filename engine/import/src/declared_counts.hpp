#pragma once
// What a mesh file's header promises, checked against the file before assimp reads it.
//
// assimp trusts the counts a header declares: it reserves memory for them (OFF, PLY) and
// loops over them, so a 309-byte OFF file declaring 3.5e11 vertices makes it allocate 15 GiB
// and abort. These checks read only the header (and, for the text formats, count the file's
// lines) and refuse a file that cannot hold what it declares, in well under a second. The
// declared face count is kept so that import_mesh can tell when faces were lost on the way.
//
// What is checked, by extension (assimp chooses its reader by the name first):
// - OFF: the counts line after the "OFF" keyword (and its variants COFF, NOFF, STOFF, ...);
//   every vertex and every face takes at least one line, as assimp reads them.
// - PLY: the element counts of the header; binary files must hold at least the fixed-size
//   part of every element, ASCII files a line per element.
// - OBJ: nothing is declared; the `f` lines are counted (one face each).
// Binary STL is binary_stl.hpp's.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace tumble::engine::detail {

/// The faces a file says it holds, and what said so ("OFF header", "PLY header", "OBJ f lines").
struct DeclaredFaces {
  std::uint64_t faces = 0;
  std::string source;
};

/// Checks the counts `file` (of `size` bytes) declares against its size; throws InputError
/// naming the file and the counts when it cannot hold them. Returns the declared face count
/// when the format gives one; nothing for other formats and for headers it does not parse
/// (assimp then reports on them).
std::optional<DeclaredFaces> check_declared_counts(const std::filesystem::path& file,
                                                   std::uintmax_t size);

}  // namespace tumble::engine::detail
