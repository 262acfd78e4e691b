#pragma once
// tumble's own reader for binary STL, the format of large scanned and printed meshes.
//
// assimp reads binary STL as well, but builds what inspection never uses: a normal for each
// face corner (36 bytes a triangle) and a heap-allocated index array for each face, before the
// engine welds the soup. On a million-triangle file assimp's read takes longer than the whole
// inspection with this reader, which maps the file, welds the corner positions straight from
// its bytes, and builds the indexed mesh in one step. Its result is the one import_mesh makes
// through assimp (the tests compare the two on every STL fixture).
//
// The format (3D Systems, "StereoLithography Interface Specification", 1988; little-endian): an
// 80-byte header, the triangle count n as uint32, then n records of 50 bytes: a normal and
// three corners as float32 triples, and a 16-bit attribute word. A file is taken as binary when
// its size is exactly 84 + 50 n, whatever its header says: assimp 5.2 decides the same way,
// also for headers that begin with "solid" like an ASCII file (the tests check both).

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>

#include "engine/geometry/triangle_mesh.hpp"

namespace tumble::engine::detail {

/// What read_binary_stl made: the welded mesh and how many corners were merged away.
struct BinaryStl {
  TriangleMesh mesh;
  std::size_t welded_vertices = 0;
};

/// Reads `file` when it is a binary STL (named *.stl, case-insensitive, of size 84 + 50 n);
/// returns nothing for any other file, which is assimp's to read. Corners at bit-identical
/// positions are welded (vertex_welding.hpp), in order of first appearance. Coordinates
/// are not checked here: non-finite ones are import_mesh's to reject. Throws InputError naming
/// the file when it cannot be read or holds more triangles than 32-bit indices can weld.
/// `size` is the file's size in bytes, which the caller has already asked for.
std::optional<BinaryStl> read_binary_stl(const std::filesystem::path& file, std::uintmax_t size);

/// Refuses a file named *.stl that is neither ASCII nor of the size its triangle count gives a
/// binary STL: a truncated or padded binary STL, which assimp would reject in its own words or
/// read as an empty ASCII file. ASCII is "solid" after leading blanks (assimp 5.2 decides by that
/// alone) with no NUL byte and none above 127 in the first 500 (or a "facet" there, for names in
/// UTF-8): a binary header may begin with "solid" too, but its count and coordinates are
/// rarely text. Throws InputError naming the
/// file, the declared count and both sizes.
void check_binary_stl_size(const std::filesystem::path& file, std::uintmax_t size);

}  // namespace tumble::engine::detail
