// The worker's scene, read and walked in the asking process (raw_scene.hpp).
//
// Node transforms are applied by walking the node tree in double precision. Vertices are
// welded on the file's own float coordinates first: an STL soup shrinks about sixfold before
// it is widened to doubles and transformed.
#include "raw_scene.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <cstring>
#include <string>

#include "base/errors.hpp"
#include "engine/geometry/vertex_welding.hpp"
#include "input_file.hpp"
#include "split_in_two.hpp"

namespace tumble::engine::detail {
namespace {

constexpr std::size_t kMaxNodeVisits = std::size_t{1} << 24;

/// Bounds-checked reading of the answer's bytes.
class SceneReader {
 public:
  SceneReader(std::span<const std::byte> bytes, const std::filesystem::path& file)
      : bytes_(bytes), file_(file) {}

  std::uint32_t u32() { return scalar<std::uint32_t>(); }
  std::uint64_t u64() { return scalar<std::uint64_t>(); }

  /// `count` items of T in place (T of 4 bytes, 4-byte aligned).
  template <typename T>
  std::span<const T> array(std::uint64_t count, const char* what) {
    static_assert(sizeof(T) == 4);
    if (count > (bytes_.size() - at_) / sizeof(T)) malformed(std::string(what) + " cut short");
    const auto* first = reinterpret_cast<const T*>(bytes_.data() + at_);
    at_ += static_cast<std::size_t>(count) * sizeof(T);
    return {first, static_cast<std::size_t>(count)};
  }

  std::string_view name() {
    const std::uint32_t length = u32();
    if (length > bytes_.size() - at_) malformed("a node name cut short");
    const std::string_view text(reinterpret_cast<const char*>(bytes_.data() + at_), length);
    at_ += (std::size_t{length} + 3) / 4 * 4;
    at_ = std::min(at_, bytes_.size());
    return text;
  }

  [[noreturn]] void malformed(const std::string& why) const {
    fail(file_, "the import worker sent a malformed scene (" + why + ")");
  }

 private:
  template <typename T>
  T scalar() {
    if (sizeof(T) > bytes_.size() - at_) malformed("cut short");
    T value;
    std::memcpy(&value, bytes_.data() + at_, sizeof value);
    at_ += sizeof value;
    return value;
  }

  std::span<const std::byte> bytes_;
  const std::filesystem::path& file_;
  std::size_t at_ = 0;
};

RawNode read_node(SceneReader& in) {
  RawNode node;
  node.name = in.name();
  const std::span<const float> transform = in.array<float>(16, "a node transform");
  std::copy(transform.begin(), transform.end(), node.transform.begin());
  node.meshes = in.array<std::uint32_t>(in.u32(), "a node's meshes");
  node.children = in.array<std::uint32_t>(in.u32(), "a node's children");
  return node;
}

RawMesh read_mesh(SceneReader& in) {
  RawMesh mesh;
  mesh.primitive_types = in.u32();
  mesh.vertices = in.u32();
  mesh.positions = in.array<float>(3 * std::uint64_t{mesh.vertices}, "a mesh's positions");
  mesh.faces = in.u32();
  mesh.all_triangles = in.u32() != 0;
  std::uint64_t corners = 3 * std::uint64_t{mesh.faces};
  if (!mesh.all_triangles) {
    mesh.corners = in.array<std::uint32_t>(mesh.faces, "a mesh's corner counts");
    corners = 0;
    for (const std::uint32_t count : mesh.corners) corners += count;
  }
  mesh.indices = in.array<std::uint32_t>(corners, "a mesh's faces");
  return mesh;
}

Eigen::Matrix4d to_eigen(const std::array<float, 16>& m) {
  Eigen::Matrix4d out;
  for (int row = 0; row < 4; ++row) {
    for (int column = 0; column < 4; ++column) out(row, column) = m[4 * row + column];
  }
  return out;
}

/// The walk of the node tree (raw_scene.hpp says what it refuses).
struct SceneWalk {
  const RawScene& scene;
  const std::filesystem::path& file;
  TriangleMesh& out;
  std::size_t welded_vertices = 0;
  std::size_t placed = 0;
  std::size_t skipped_faces = 0;
  std::size_t visits = 0;
  bool any_transform = false;

  void collect(std::uint32_t node, const Eigen::Matrix4d& parent, unsigned depth);
  void add_mesh(const RawMesh& mesh, const Eigen::Matrix4d& transform);
  void add_faces(const RawMesh& mesh, std::uint32_t index, std::uint32_t base, const WeldMap& weld,
                 bool mirrored);
};

/// Appends the triangles of every mesh below `index`, transformed into the file's root frame.
void SceneWalk::collect(std::uint32_t index, const Eigen::Matrix4d& parent, unsigned depth) {
  // A cycle in the node tree would recurse forever; no real file nests this deep.
  if (depth > 1000) fail(file, "assimp returned a node tree more than 1000 levels deep");
  // Nodes shared between parents are walked once per parent: a scene that shares them over
  // and over would take for ever. No real file places its nodes this many times.
  if (++visits > kMaxNodeVisits) {
    fail(file, "assimp returned a node tree of more than " + std::to_string(kMaxNodeVisits) +
                   " placed nodes");
  }
  const RawNode& node = scene.nodes[index];
  const Eigen::Matrix4d transform = parent * to_eigen(node.transform);
  for (const std::uint32_t mesh : node.meshes) {
    if (mesh >= scene.meshes.size()) {
      fail(file, "assimp returned a broken scene: node '" + std::string(node.name) +
                     "' refers to mesh " + std::to_string(mesh) + ", which does not exist");
    }
    add_mesh(scene.meshes[mesh], transform);
  }
  for (std::size_t child = 0; child < node.children.size(); ++child) {
    if (node.children[child] >= scene.nodes.size()) {
      fail(file, "assimp returned a broken scene: child " + std::to_string(child + 1) +
                     " of node '" + std::string(node.name) +
                     "' is missing, so some of the file's meshes would be lost");
    }
    collect(node.children[child], transform, depth + 1);
  }
}

void SceneWalk::add_mesh(const RawMesh& mesh, const Eigen::Matrix4d& transform) {
  // Points and lines (meshes of them after aiProcess_SortByPType) enclose nothing.
  if (!(mesh.primitive_types & kRawTriangleBit)) {
    skipped_faces += mesh.faces;
    return;
  }
  const Eigen::Matrix3d linear = transform.topLeftCorner<3, 3>();
  const Eigen::Vector3d translation = transform.topRightCorner<3, 1>();
  // A mirroring transform turns outward normals inward: reverse the winding to compensate.
  const bool mirrored = linear.determinant() < 0.0;
  const bool identity = transform.isIdentity(0.0);
  const float* const coordinates = mesh.positions.data();
  const WeldMap weld = weld_positions<float>(mesh.vertices, [&](std::size_t v) {
    return std::array<float, 3>{coordinates[3 * v], coordinates[3 * v + 1], coordinates[3 * v + 2]};
  });
  welded_vertices += mesh.vertices - weld.kept.size();
  ++placed;
  any_transform = any_transform || !identity;

  // Widen (and place) the survivors. The output arrays are fresh memory of ~12 MB each for a
  // million triangles: huge pages, and both halves faulted in at once by two threads.
  const auto base = static_cast<std::uint32_t>(out.positions.size());
  const std::size_t survivors = weld.kept.size();
  out.positions.reserve(base + survivors);
  advise_huge_pages(out.positions.data() + base, survivors * sizeof(Eigen::Vector3d));
  out.positions.resize(base + survivors);  // Eigen leaves the new vectors uninitialised
  Eigen::Vector3d* const positions = out.positions.data() + base;
  split_in_two(survivors, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const float* const p = coordinates + 3 * std::size_t{weld.kept[i]};
      const Eigen::Vector3d position(p[0], p[1], p[2]);
      positions[i] = identity ? position : Eigen::Vector3d(linear * position + translation);
    }
  });
  const auto index = static_cast<std::uint32_t>(&mesh - scene.meshes.data());
  add_faces(mesh, index, base, weld, mirrored);
}

/// Faces to welded triangles. When every face is a triangle (STL always), each lands at a known
/// place, so large meshes are split between two threads; a vertex index out of range sends the
/// mesh to the checking loop, which names the face.
void SceneWalk::add_faces(const RawMesh& mesh, std::uint32_t index, std::uint32_t base,
                          const WeldMap& weld, bool mirrored) {
  const std::uint32_t vertices = mesh.vertices;
  const auto triangle_of = [&](const std::uint32_t* corner) {
    const std::uint32_t a = base + weld.new_index[corner[0]];
    const std::uint32_t b = base + weld.new_index[corner[1]];
    const std::uint32_t c = base + weld.new_index[corner[2]];
    return mirrored ? std::array{a, c, b} : std::array{a, b, c};
  };
  const auto inside = [vertices](const std::uint32_t* corner, std::uint32_t count) {
    return std::all_of(corner, corner + count,
                       [vertices](std::uint32_t v) { return v < vertices; });
  };
  const std::size_t first = out.triangles.size();
  const std::size_t faces = mesh.faces;
  if (mesh.all_triangles) {
    out.triangles.reserve(first + faces);
    advise_huge_pages(out.triangles.data() + first, faces * sizeof(out.triangles[0]));
    out.triangles.resize(first + faces);
    std::array<std::uint32_t, 3>* const triangles = out.triangles.data() + first;
    std::array<bool, 2> clean = {true, true};  // one flag per thread
    split_in_two(faces, [&](std::size_t begin, std::size_t end) {
      bool ok = true;
      for (std::size_t f = begin; f < end && ok; ++f) {
        const std::uint32_t* const corner = mesh.indices.data() + 3 * f;
        ok = inside(corner, 3);
        if (ok) triangles[f] = triangle_of(corner);
      }
      clean[begin == 0 ? 0 : 1] = ok;
    });
    if (clean[0] && clean[1]) return;
    out.triangles.resize(first);
  }
  const std::size_t listed = mesh.all_triangles ? 3 : 0;
  const std::uint32_t* corner = mesh.indices.data();
  out.triangles.reserve(first + faces);
  for (std::size_t f = 0; f < faces; ++f) {
    const std::uint32_t count = listed ? 3u : mesh.corners[f];
    const std::uint32_t* const face = corner;
    corner += count;
    if (count < 3) {  // a point or a line: no area, nothing to weigh
      ++skipped_faces;
      continue;
    }
    if (count > 3) {
      fail(file, "assimp returned a broken scene: face " + std::to_string(f + 1) + " of mesh " +
                     std::to_string(index) + " has " + std::to_string(count) +
                     " corners in a mesh of triangles");
    }
    if (!inside(face, 3)) {
      fail(file, "assimp returned a broken scene: face " + std::to_string(f + 1) + " of mesh " +
                     std::to_string(index) + " refers to a vertex past the mesh's " +
                     std::to_string(vertices) + " vertices");
    }
    out.triangles.push_back(triangle_of(face));
  }
}

}  // namespace

RawScene decode_raw_scene(std::span<const std::byte> bytes, const std::filesystem::path& file) {
  SceneReader in(bytes, file);
  if (in.u32() != kRawSceneMagic || in.u32() != kRawSceneVersion) {
    in.malformed("not a scene of this tumble's import worker");
  }
  RawScene scene;
  scene.faces_read = in.u64();
  scene.skeleton_only = (in.u32() & kRawSkeletonOnly) != 0;
  const std::uint32_t nodes = in.u32();
  const std::uint32_t meshes = in.u32();
  // Every node and mesh takes at least 16 bytes: a count past that is malformed, not a reason
  // to reserve gigabytes.
  if (nodes == 0 || nodes > bytes.size() / 16 || meshes > bytes.size() / 16) {
    in.malformed("impossible node or mesh count");
  }
  scene.nodes.reserve(nodes);
  for (std::uint32_t n = 0; n < nodes; ++n) scene.nodes.push_back(read_node(in));
  scene.meshes.reserve(meshes);
  for (std::uint32_t m = 0; m < meshes; ++m) scene.meshes.push_back(read_mesh(in));
  return scene;
}

TriangleMesh walk_raw_scene(const RawScene& scene, const std::filesystem::path& file,
                            ImportStats& stats) {
  TriangleMesh mesh;
  SceneWalk walk{scene, file, mesh};
  if (!scene.nodes.empty()) walk.collect(0, Eigen::Matrix4d::Identity(), 0);
  stats.welded_vertices = walk.welded_vertices;
  stats.distinct_positions = walk.placed == 1 && !walk.any_transform;
  stats.skipped_faces = walk.skipped_faces;
  if (walk.skipped_faces > 0) {
    stats.warnings.push_back(
        "skipped " + std::to_string(walk.skipped_faces) +
        (walk.skipped_faces == 1 ? " face" : " faces") +
        " of fewer than three corners (points and lines, which enclose nothing)");
  }
  return mesh;
}

}  // namespace tumble::engine::detail
