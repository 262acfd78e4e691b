// Mesh import through assimp.
//
// Post-processing is kept to triangulation (points and lines are skipped while collecting; asking
// assimp to remove them makes it fail on files that have nothing else): no
// aiProcess_JoinIdenticalVertices (slow, and it compares normals: the engine welds by position
// itself) and no aiProcess_FindDegenerates (its area threshold is absolute and deletes whole
// small meshes). Node transforms are applied by walking the node tree in double precision.
#include "engine/import/mesh_import.hpp"

#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <Eigen/LU>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <new>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "base/errors.hpp"
#include "binary_stl.hpp"
#include "declared_counts.hpp"
#include "engine/geometry/vertex_welding.hpp"
#include "import_worker.hpp"
#include "input_file.hpp"
#include "isolated_import.hpp"
#include "split_in_two.hpp"

namespace tumble::engine {
namespace {

using detail::fail;
using detail::split_in_two;

/// One line of assimp's error text.
std::string single_line(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  while (!text.empty() && (text.back() == ' ' || text.back() == '\r')) text.pop_back();
  return text;
}

Eigen::Matrix4d to_eigen(const aiMatrix4x4& m) {
  Eigen::Matrix4d out;
  out << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3,
      m.d4;
  return out;
}

/// The walk of assimp's node tree, checking what assimp returned before using it: a null
/// node or mesh, a mesh index past the scene's meshes or a vertex index past the mesh's
/// vertices is refused (assimp 5.2 leaves a null child in some RAW scenes). Faces that are not
/// triangles are skipped even in a mesh flagged as triangles only (assimp 5.2 flags OBJ faces
/// of one or two corners so).
struct SceneWalk {
  const aiScene& scene;
  const std::filesystem::path& file;
  TriangleMesh& out;
  std::size_t welded_vertices = 0;
  std::size_t placed = 0;
  std::size_t skipped_faces = 0;
  bool any_transform = false;

  void collect(const aiNode& node, const Eigen::Matrix4d& parent, unsigned depth);
  void add_mesh(const aiMesh& mesh, unsigned index, const Eigen::Matrix4d& transform);
  void add_faces(const aiMesh& mesh, unsigned index, std::uint32_t base, const WeldMap& weld,
                 bool mirrored);
};

/// Appends the triangles of every mesh below `node`, transformed into the file's root frame.
void SceneWalk::collect(const aiNode& node, const Eigen::Matrix4d& parent, unsigned depth) {
  // A cycle in the node tree would recurse forever; no real file nests this deep.
  if (depth > 1000) fail(file, "assimp returned a node tree more than 1000 levels deep");
  const Eigen::Matrix4d transform = parent * to_eigen(node.mTransformation);
  for (unsigned m = 0; m < node.mNumMeshes; ++m) {
    const unsigned index = node.mMeshes[m];
    if (index >= scene.mNumMeshes || scene.mMeshes[index] == nullptr) {
      fail(file, "assimp returned a broken scene: node '" + std::string(node.mName.C_Str()) +
                     "' refers to mesh " + std::to_string(index) + ", which does not exist");
    }
    add_mesh(*scene.mMeshes[index], index, transform);
  }
  for (unsigned child = 0; child < node.mNumChildren; ++child) {
    if (node.mChildren[child] == nullptr) {
      fail(file, "assimp returned a broken scene: child " + std::to_string(child + 1) +
                     " of node '" + std::string(node.mName.C_Str()) +
                     "' is missing, so some of the file's meshes would be lost");
    }
    collect(*node.mChildren[child], transform, depth + 1);
  }
}

void SceneWalk::add_mesh(const aiMesh& mesh, unsigned index, const Eigen::Matrix4d& transform) {
  // Points and lines (meshes of them after aiProcess_SortByPType) enclose nothing.
  if (!(mesh.mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) {
    skipped_faces += mesh.mNumFaces;
    return;
  }
  const Eigen::Matrix3d linear = transform.topLeftCorner<3, 3>();
  const Eigen::Vector3d translation = transform.topRightCorner<3, 1>();
  // A mirroring transform turns outward normals inward: reverse the winding to compensate.
  const bool mirrored = linear.determinant() < 0.0;
  const bool identity = transform.isIdentity(0.0);

  // Weld on assimp's own coordinates first: an STL soup shrinks about sixfold before it is
  // widened to doubles and transformed. The normals assimp read (STL files carry them, 12
  // bytes per vertex) are never used: the weld works in their memory, which assimp has
  // already faulted in, rather than in fresh pages. The scene is discarded after this walk.
  std::span<std::byte> scratch;
  if (mesh.mNormals != nullptr) {
    scratch = {reinterpret_cast<std::byte*>(mesh.mNormals),
               std::size_t{mesh.mNumVertices} * sizeof(aiVector3D)};
  }
  const WeldMap weld = weld_positions<ai_real>(
      mesh.mNumVertices,
      [&](std::size_t v) {
        const aiVector3D& p = mesh.mVertices[v];
        return std::array<ai_real, 3>{p.x, p.y, p.z};
      },
      scratch);
  welded_vertices += mesh.mNumVertices - weld.kept.size();
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
  const auto widen = [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const aiVector3D& p = mesh.mVertices[weld.kept[i]];
      const Eigen::Vector3d position(p.x, p.y, p.z);
      positions[i] = identity ? position : Eigen::Vector3d(linear * position + translation);
    }
  };
  split_in_two(survivors, widen);
  add_faces(mesh, index, base, weld, mirrored);
}

/// Faces to welded triangles. When every face is a well-formed triangle (STL always), each
/// lands at a known place, so large meshes are split between two threads; a face with another
/// corner count or a vertex index out of range sends the mesh to the checking loop.
void SceneWalk::add_faces(const aiMesh& mesh, unsigned index, std::uint32_t base,
                          const WeldMap& weld, bool mirrored) {
  const unsigned vertices = mesh.mNumVertices;
  const auto valid = [vertices](const aiFace& face) {
    return face.mNumIndices == 3 && face.mIndices != nullptr && face.mIndices[0] < vertices &&
           face.mIndices[1] < vertices && face.mIndices[2] < vertices;
  };
  const auto triangle_of = [&](const aiFace& face) {
    const std::uint32_t a = base + weld.new_index[face.mIndices[0]];
    const std::uint32_t b = base + weld.new_index[face.mIndices[1]];
    const std::uint32_t c = base + weld.new_index[face.mIndices[2]];
    return mirrored ? std::array{a, c, b} : std::array{a, b, c};
  };
  const std::size_t first = out.triangles.size();
  const std::size_t faces = mesh.mNumFaces;
  if (mesh.mPrimitiveTypes == aiPrimitiveType_TRIANGLE) {
    out.triangles.reserve(first + faces);
    advise_huge_pages(out.triangles.data() + first, faces * sizeof(out.triangles[0]));
    out.triangles.resize(first + faces);
    std::array<std::uint32_t, 3>* const triangles = out.triangles.data() + first;
    std::array<bool, 2> clean = {true, true};  // one flag per thread
    split_in_two(faces, [&](std::size_t begin, std::size_t end) {
      bool ok = true;
      for (std::size_t f = begin; f < end && ok; ++f) {
        ok = valid(mesh.mFaces[f]);
        if (ok) triangles[f] = triangle_of(mesh.mFaces[f]);
      }
      clean[begin == 0 ? 0 : 1] = ok;
    });
    if (clean[0] && clean[1]) return;
    out.triangles.resize(first);
  }
  out.triangles.reserve(first + faces);
  for (std::size_t f = 0; f < faces; ++f) {
    const aiFace& face = mesh.mFaces[f];
    if (face.mNumIndices < 3) {  // a point or a line: no area, nothing to weigh
      ++skipped_faces;
      continue;
    }
    if (face.mNumIndices > 3) {
      fail(file, "assimp returned a broken scene: face " + std::to_string(f + 1) + " of mesh " +
                     std::to_string(index) + " has " + std::to_string(face.mNumIndices) +
                     " corners in a mesh of triangles");
    }
    if (!valid(face)) {
      fail(file, "assimp returned a broken scene: face " + std::to_string(f + 1) + " of mesh " +
                     std::to_string(index) + " refers to a vertex past the mesh's " +
                     std::to_string(vertices) + " vertices");
    }
    out.triangles.push_back(triangle_of(face));
  }
}

/// What kind of thing a path that is not a regular file names.
std::string kind_of(std::filesystem::file_type type) {
  switch (type) {
    case std::filesystem::file_type::directory:
      return "is a directory, not a mesh file";
    case std::filesystem::file_type::fifo:
      return "is a FIFO (named pipe), not a regular file";
    case std::filesystem::file_type::socket:
      return "is a socket, not a regular file";
    case std::filesystem::file_type::block:
      return "is a block device, not a regular file";
    case std::filesystem::file_type::character:
      return "is a character device, not a regular file";
    default:
      return "is not a regular file";
  }
}

/// Says plainly what is wrong with the path before anything opens it (opening a FIFO would
/// block until a writer comes), and returns the file's size.
std::uintmax_t checked_size(const std::filesystem::path& file) {
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(file, error);
  if (error == std::errc::too_many_symbolic_link_levels) {
    fail(file, "is a loop of symbolic links");
  }
  if (status.type() == std::filesystem::file_type::not_found) {
    std::error_code link_error;
    if (std::filesystem::is_symlink(std::filesystem::symlink_status(file, link_error))) {
      fail(file, "is a symbolic link to a missing file (" +
                     std::filesystem::read_symlink(file, link_error).string() + ")");
    }
    fail(file, "no such file");
  }
  if (error) fail(file, "cannot be examined (" + error.message() + ")");
  if (status.type() != std::filesystem::file_type::regular) fail(file, kind_of(status.type()));
  const std::uintmax_t size = std::filesystem::file_size(file, error);
  if (error) fail(file, "cannot be examined (" + error.message() + ")");
  if (size == 0) fail(file, "is empty");
  return size;
}

/// Checks the scene as assimp read it, before any post-processing reads it too: every mesh
/// present, with positions, and every face index inside its mesh. Returns the count of faces
/// that have any corner (assimp leaves empty faces where an OFF file ran short).
std::uint64_t validate_scene(const aiScene& scene, const std::filesystem::path& file) {
  if (scene.mRootNode == nullptr || scene.mNumMeshes == 0) fail(file, "contains no triangles");
  if (scene.mMeshes == nullptr) fail(file, "assimp returned a broken scene: no mesh array");
  std::uint64_t faces = 0;
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh* const mesh = scene.mMeshes[m];
    const std::string name = "mesh " + std::to_string(m);
    if (mesh == nullptr) fail(file, "assimp returned a broken scene: " + name + " is missing");
    if (mesh->mNumVertices > 0 && mesh->mVertices == nullptr) {
      fail(file, "assimp returned a broken scene: " + name + " has no vertex positions");
    }
    if (mesh->mNumFaces > 0 && mesh->mFaces == nullptr) {
      fail(file, "assimp returned a broken scene: " + name + " has no faces");
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices == 0) continue;
      ++faces;
      const bool listed = face.mIndices != nullptr;
      for (unsigned i = 0; i < face.mNumIndices; ++i) {
        if (listed && face.mIndices[i] < mesh->mNumVertices) continue;
        fail(file, "face " + std::to_string(f + 1) + " of " + name + " refers to vertex index " +
                       (listed ? std::to_string(face.mIndices[i]) : "?") + ", but the mesh has " +
                       std::to_string(mesh->mNumVertices) + " vertices (indices from 0)");
      }
    }
  }
  return faces;
}

/// Refuses a file whose faces did not all arrive: tumble never reports the mass properties of
/// less than the file holds.
void require_all_faces(const std::filesystem::path& file,
                       const std::optional<detail::DeclaredFaces>& declared,
                       std::uint64_t imported) {
  if (!declared || imported >= declared->faces) return;
  const bool obj = declared->source == "OBJ f lines";
  fail(file, (obj ? "has " + std::to_string(declared->faces) + " face lines ('f')"
                  : "the " + declared->source + " declares " + std::to_string(declared->faces) +
                        " faces") +
                 ", but assimp read only " + std::to_string(imported) +
                 ": the rest were dropped (malformed or truncated), so the mass properties "
                 "would be those of part of the file");
}

/// True when every mesh of the scene is the placeholder assimp builds for a skeleton (the bones
/// of a motion capture, CSM and BVH): it shows the joints, and encloses nothing of a body.
bool only_skeleton_placeholders(const aiScene& scene) {
  if (scene.mNumAnimations == 0 || scene.mMaterials == nullptr) return false;
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const unsigned material = scene.mMeshes[m]->mMaterialIndex;
    if (material >= scene.mNumMaterials || scene.mMaterials[material] == nullptr) return false;
    aiString name;
    if (scene.mMaterials[material]->Get(AI_MATKEY_NAME, name) != AI_SUCCESS ||
        std::string_view(name.C_Str()) != "SkeletonMaterial") {
      return false;
    }
  }
  return true;
}

/// Reads the file with assimp (every format it knows) and collects its meshes.
TriangleMesh import_with_assimp(const std::filesystem::path& file,
                                const std::optional<detail::DeclaredFaces>& declared,
                                ImportStats& stats) {
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(file.string(), 0);
  if (scene != nullptr) require_all_faces(file, declared, validate_scene(*scene, file));
  if (scene != nullptr && only_skeleton_placeholders(*scene)) {
    fail(file,
         "holds no solid, only an animated skeleton (motion capture): the mesh assimp "
         "makes to show its bones is a placeholder, not a body");
  }
  // Triangulate only when the file has polygons (STL never does).
  const auto has_non_triangles = [](const aiScene& s) {
    for (unsigned m = 0; m < s.mNumMeshes; ++m) {
      if (s.mMeshes[m]->mPrimitiveTypes & ~aiPrimitiveType_TRIANGLE) return true;
    }
    return false;
  };
  if (scene != nullptr && has_non_triangles(*scene)) {
    scene = importer.ApplyPostProcessing(aiProcess_Triangulate | aiProcess_SortByPType);
    if (scene != nullptr) validate_scene(*scene, file);
  }
  if (scene == nullptr) {
    const std::string reason = single_line(importer.GetErrorString());
    // assimp catches the allocation failure the memory limit causes: pass it on as such.
    if (reason.find("bad_alloc") != std::string::npos) throw std::bad_alloc();
    if (reason.find("No suitable reader") != std::string::npos) {
      fail(file, "unknown or unsupported mesh format");
    }
    fail(file, "cannot be read as a mesh (assimp: " + reason + ")");
  }

  TriangleMesh mesh;
  SceneWalk walk{*scene, file, mesh};
  walk.collect(*scene->mRootNode, Eigen::Matrix4d::Identity(), 0);
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

/// The worker's side of import_mesh (a WorkerTask): the request is the file's path, then,
/// when its face count was declared, the count and where it was declared.
TriangleMesh import_request(const std::vector<std::string>& request, ImportStats& stats) {
  std::optional<detail::DeclaredFaces> declared;
  if (request.size() == 3) declared = detail::DeclaredFaces{std::stoull(request[1]), request[2]};
  return import_with_assimp(request.at(0), declared, stats);
}

}  // namespace

TriangleMesh import_mesh(const std::filesystem::path& file, ImportStats* stats,
                         StlReader stl_reader, const ImportLimits& limits) {
  const std::uintmax_t size = checked_size(file);
  ImportStats local;
  if (stats == nullptr) stats = &local;

  // Binary STL is read by tumble's own reader unless assimp is asked for.
  TriangleMesh mesh;
  std::optional<detail::BinaryStl> stl;
  if (stl_reader == StlReader::tumble) stl = detail::read_binary_stl(file, size);
  if (stl) {
    mesh = std::move(stl->mesh);
    stats->welded_vertices = stl->welded_vertices;
    stats->distinct_positions = true;  // one mesh, no transform, welded as a whole
    stats->own_stl_reader = true;
  } else {
    if (!std::ifstream(file, std::ios::binary)) fail(file, "cannot be opened for reading");
    // What the header declares is checked before assimp trusts it (declared_counts.hpp).
    detail::check_binary_stl_size(file, size);
    const std::optional<detail::DeclaredFaces> declared = detail::check_declared_counts(file, size);
    // assimp reads in this thread's import worker, under limits (import_worker.hpp).
    std::vector<std::string> request{file.string()};
    if (declared)
      request.insert(request.end(), {std::to_string(declared->faces), declared->source});
    mesh = detail::run_in_worker(file, detail::effective_limits(limits, size), "assimp", *stats,
                                 import_request, request);
  }
  if (mesh.triangles.empty()) fail(file, "contains no triangles");
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    if (!mesh.positions[i].allFinite()) {
      fail(file, "vertex " + std::to_string(i + 1) + " has a non-finite coordinate");
    }
  }
  return mesh;
}

}  // namespace tumble::engine
