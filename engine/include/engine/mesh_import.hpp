#pragma once
/// @file Reading meshes with assimp (kept apart: the dynamics never include it).

#include <filesystem>

#include "engine/triangle_mesh.hpp"

namespace tumble::engine {

/// Reads every mesh of a file assimp understands (STL, OBJ, PLY, OFF, glTF 2.0, FBX, ...) into
/// one unwelded triangle mesh, with each node's accumulated transform applied (a mirroring
/// transform reverses the winding so normals stay outward). Polygons are triangulated; points
/// and lines are ignored. Throws InputError naming the file when it cannot be read, has an
/// unknown format, holds no triangles or has non-finite coordinates.
TriangleMesh import_mesh(const std::filesystem::path& file);

}  // namespace tumble::engine
