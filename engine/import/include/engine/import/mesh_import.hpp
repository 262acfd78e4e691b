#pragma once
/// @file Reading mesh files: binary STL by tumble's own reader, every other format by assimp in
/// a process of its own (the import worker, tumble-import; assimp is never loaded into the
/// caller's process).

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "engine/geometry/triangle_mesh.hpp"

namespace tumble::engine {

/// What import_mesh did on the way.
struct ImportStats {
  std::size_t welded_vertices = 0;  ///< vertices merged within each of the file's meshes
  /// True when the whole file was one mesh placed once without a transform: its welded
  /// positions are then already distinct, and the analysis need not weld them again.
  bool distinct_positions = false;
  /// True when tumble's own binary STL reader read the file rather than assimp.
  bool own_stl_reader = false;
  /// Faces of one or two corners (points, lines) found among triangles and skipped.
  std::size_t skipped_faces = 0;
  /// What the caller should pass on to the user (skipped faces): one sentence each, without
  /// the file's name; `tumble inspect` appends them to the report's warnings.
  std::vector<std::string> warnings;
};

/// Who reads binary STL files. tumble's own reader (the default) welds the corners straight
/// from the file's bytes and gives the same mesh as assimp in a fraction of the time; assimp
/// is kept selectable to compare the two (tests, benchmarks). Other formats, ASCII STL
/// included, are always assimp's.
enum class StlReader { tumble, assimp };

/// Bounds on assimp's reading of one file. assimp runs in the import worker, a program of its
/// own that tumble starts (never a fork of the caller), under these limits, so that its own faults
/// on malformed files (crashes, endless loops, runaway memory, leaks) end in a refusal naming the
/// file instead of taking tumble down. Zero means the default, which grows with the file's size.
struct ImportLimits {
  double cpu_seconds = 0.0;        ///< default: 10 s + 2 s per whole MiB of file
  std::uint64_t memory_bytes = 0;  ///< default: 2 GiB + 64 bytes per byte of file (at most RAM)
};

/// Reads every mesh of a file assimp understands (STL, OBJ, PLY, OFF, glTF 2.0, FBX, ...) into
/// one triangle mesh, with each node's accumulated transform applied (a mirroring transform
/// reverses the winding so normals stay outward). Vertices at identical positions within each
/// of the file's meshes are welded on the way; those shared between meshes are left to
/// weld_by_position. Polygons are triangulated; points and lines are ignored. Binary STL goes
/// to tumble's own reader unless `stl_reader` asks for assimp (the mesh is the same). Throws
/// InputError naming the file when it cannot be read, has an unknown format, holds no
/// triangles or has non-finite coordinates, and when assimp crashes on it or exceeds `limits`.
TriangleMesh import_mesh(const std::filesystem::path& file, ImportStats* stats = nullptr,
                         StlReader stl_reader = StlReader::tumble, const ImportLimits& limits = {});

}  // namespace tumble::engine
