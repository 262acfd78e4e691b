#pragma once
// A scene as assimp returned it, sent by the import worker (tumble-import) to the process that
// asked for it, which checks and walks it into one triangle mesh. Everything the walk refuses
// (a node that names a missing mesh or child, a face past its mesh's vertices, a tree deeper
// than any real file) is decided here, in the asking process, where the sanitizers and the
// fuzzers see it; the worker only reads the file, checks what assimp's own post-processing
// would trip on, triangulates and writes the scene out.
//
// The format (native byte order; every array 4-byte aligned from the payload's start):
//   u32 magic "TSCN", u32 version
//   u64 faces assimp read (before triangulation, faces with at least one corner)
//   u32 flags (bit 0: every mesh is a skeleton's placeholder), u32 node count, u32 mesh count
//   then each node: u32 name length, name bytes (padded), 16 f32 transform (row major),
//                   u32 mesh count, u32 mesh indices, u32 child count, u32 child indices
//                   (kMissingNode for a child assimp left null)
//   then each mesh: u32 primitive types (assimp's aiPrimitiveType bits), u32 vertex count,
//                   3 f32 per vertex, u32 face count, u32 all-triangles (1: 3 indices a face
//                   follow; 0: a corner count a face, then the indices of all faces)
// Nodes are numbered in the order written; node 0 is the root. A node reached twice (assimp
// shares a node between parents) is written once and named by its number.

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string_view>
#include <vector>

#include "engine/geometry/triangle_mesh.hpp"
#include "engine/import/mesh_import.hpp"

namespace tumble::engine::detail {

inline constexpr std::uint32_t kRawSceneMagic = 0x4e435354;  // "TSCN"
inline constexpr std::uint32_t kRawSceneVersion = 1;
inline constexpr std::uint32_t kMissingNode = 0xffffffffu;
/// assimp's aiPrimitiveType_TRIANGLE (the bit the walk keeps).
inline constexpr std::uint32_t kRawTriangleBit = 0x4;
/// The flag of a scene whose meshes are all a skeleton's placeholders.
inline constexpr std::uint32_t kRawSkeletonOnly = 0x1;

struct RawNode {
  std::string_view name;
  std::array<float, 16> transform{};  ///< row major, as aiMatrix4x4
  std::span<const std::uint32_t> meshes;
  std::span<const std::uint32_t> children;
};

struct RawMesh {
  std::uint32_t primitive_types = 0;
  std::uint32_t vertices = 0;
  std::span<const float> positions;  ///< 3 a vertex
  std::uint32_t faces = 0;
  bool all_triangles = false;
  std::span<const std::uint32_t> corners;  ///< a count a face; empty when all_triangles
  std::span<const std::uint32_t> indices;  ///< every face's corners, in order
};

struct RawScene {
  std::uint64_t faces_read = 0;
  bool skeleton_only = false;
  std::vector<RawNode> nodes;
  std::vector<RawMesh> meshes;
};

/// Reads the worker's answer. Spans point into `bytes`, which must outlive the scene and be
/// 8-byte aligned. Throws InputError "FILE: the import worker sent a malformed scene (...)"
/// for anything cut short or out of range, never reading past `bytes`.
RawScene decode_raw_scene(std::span<const std::byte> bytes, const std::filesystem::path& file);

/// Walks the node tree from the root, placing each mesh's triangles by its node's accumulated
/// transform (a mirroring transform reverses the winding so normals stay outward), welding
/// vertices at identical positions within each mesh, and skipping points and lines (counted
/// in `stats`). Refuses with an InputError naming `file` a node that names a missing mesh or
/// child, a face past its mesh's vertices or with more than three corners, and a tree more
/// than 1000 levels deep.
TriangleMesh walk_raw_scene(const RawScene& scene, const std::filesystem::path& file,
                            ImportStats& stats);

}  // namespace tumble::engine::detail
