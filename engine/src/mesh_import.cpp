// Mesh import through assimp.
//
// Post-processing is kept to triangulation (points and lines are skipped while collecting; asking
// assimp to remove them makes it fail on files that have nothing else): no
// aiProcess_JoinIdenticalVertices (slow, and it compares normals: the engine welds by position
// itself) and no aiProcess_FindDegenerates (its area threshold is absolute and deletes whole
// small meshes). Node transforms are applied by walking the node tree in double precision.
#include "engine/mesh_import.hpp"

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <Eigen/LU>

#include <algorithm>
#include <fstream>
#include <span>
#include <system_error>

#include "binary_stl.hpp"
#include "engine/input_error.hpp"
#include "split_in_two.hpp"
#include "vertex_welding.hpp"

namespace tumble::engine {
namespace {

using detail::split_in_two;

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& problem) {
  throw InputError(file.string() + ": " + problem);
}

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

/// Appends the triangles of every mesh below `node`, transformed into the file's root frame.
void collect(const aiScene& scene, const aiNode& node, const Eigen::Matrix4d& parent,
             TriangleMesh& out, std::size_t& welded_vertices, std::size_t& placed,
             bool& any_transform) {
  const Eigen::Matrix4d transform = parent * to_eigen(node.mTransformation);
  const Eigen::Matrix3d linear = transform.topLeftCorner<3, 3>();
  const Eigen::Vector3d translation = transform.topRightCorner<3, 1>();
  // A mirroring transform turns outward normals inward: reverse the winding to compensate.
  const bool mirrored = linear.determinant() < 0.0;
  const bool identity = transform.isIdentity(0.0);

  for (unsigned m = 0; m < node.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[node.mMeshes[m]];
    if (!(mesh.mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
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

    // Faces to welded triangles. When every face is a triangle (STL always), each lands at a
    // known place, so large meshes are split between two threads.
    const auto triangle_of = [&](const aiFace& face) {
      const std::uint32_t a = base + weld.new_index[face.mIndices[0]];
      const std::uint32_t b = base + weld.new_index[face.mIndices[1]];
      const std::uint32_t c = base + weld.new_index[face.mIndices[2]];
      return mirrored ? std::array{a, c, b} : std::array{a, b, c};
    };
    if (mesh.mPrimitiveTypes == aiPrimitiveType_TRIANGLE) {
      const std::size_t first = out.triangles.size();
      const std::size_t faces = mesh.mNumFaces;
      out.triangles.reserve(first + faces);
      advise_huge_pages(out.triangles.data() + first, faces * sizeof(out.triangles[0]));
      out.triangles.resize(first + faces);
      std::array<std::uint32_t, 3>* const triangles = out.triangles.data() + first;
      split_in_two(faces, [&](std::size_t begin, std::size_t end) {
        for (std::size_t f = begin; f < end; ++f) triangles[f] = triangle_of(mesh.mFaces[f]);
      });
    } else {
      out.triangles.reserve(out.triangles.size() + mesh.mNumFaces);
      for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
        if (mesh.mFaces[f].mNumIndices == 3) out.triangles.push_back(triangle_of(mesh.mFaces[f]));
      }
    }
  }
  for (unsigned child = 0; child < node.mNumChildren; ++child) {
    collect(scene, *node.mChildren[child], transform, out, welded_vertices, placed, any_transform);
  }
}

/// Reads the file with assimp (every format it knows) and collects its meshes.
TriangleMesh import_with_assimp(const std::filesystem::path& file, ImportStats* stats) {
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(file.string(), 0);
  // Triangulate only when the file has polygons (STL never does).
  const auto has_non_triangles = [](const aiScene& s) {
    for (unsigned m = 0; m < s.mNumMeshes; ++m) {
      if (s.mMeshes[m]->mPrimitiveTypes & ~aiPrimitiveType_TRIANGLE) return true;
    }
    return false;
  };
  if (scene != nullptr && has_non_triangles(*scene)) {
    scene = importer.ApplyPostProcessing(aiProcess_Triangulate | aiProcess_SortByPType);
  }
  if (scene == nullptr) {
    const std::string reason = single_line(importer.GetErrorString());
    if (reason.find("No suitable reader") != std::string::npos) {
      fail(file, "unknown or unsupported mesh format");
    }
    fail(file, "cannot be read as a mesh (assimp: " + reason + ")");
  }
  if (scene->mRootNode == nullptr || scene->mNumMeshes == 0) fail(file, "contains no triangles");

  TriangleMesh mesh;
  std::size_t welded = 0, placed = 0;
  bool any_transform = false;
  collect(*scene, *scene->mRootNode, Eigen::Matrix4d::Identity(), mesh, welded, placed,
          any_transform);
  if (stats != nullptr) {
    stats->welded_vertices = welded;
    stats->distinct_positions = placed == 1 && !any_transform;
  }
  return mesh;
}

}  // namespace

TriangleMesh import_mesh(const std::filesystem::path& file, ImportStats* stats,
                         StlReader stl_reader) {
  // Say plainly what is wrong with the path before assimp does it vaguely.
  std::error_code error;
  const auto status = std::filesystem::status(file, error);
  if (!std::filesystem::exists(status)) fail(file, "no such file");
  if (std::filesystem::is_directory(status)) fail(file, "is a directory, not a mesh file");
  const std::uintmax_t size = std::filesystem::file_size(file, error);
  if (!error && size == 0) fail(file, "is empty");

  // Binary STL is read by tumble's own reader unless assimp is asked for.
  TriangleMesh mesh;
  std::optional<detail::BinaryStl> stl;
  if (stl_reader == StlReader::tumble && !error) stl = detail::read_binary_stl(file, size);
  if (stl) {
    mesh = std::move(stl->mesh);
    if (stats != nullptr) {
      stats->welded_vertices = stl->welded_vertices;
      stats->distinct_positions = true;  // one mesh, no transform, welded as a whole
      stats->own_stl_reader = true;
    }
  } else {
    if (!std::ifstream(file, std::ios::binary)) fail(file, "cannot be opened for reading");
    mesh = import_with_assimp(file, stats);
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
