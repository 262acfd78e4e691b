// The import worker's one task: read a file with assimp and write the scene out as assimp
// returned it (engine/import/src/raw_scene.hpp gives the format).
//
// Post-processing is kept to triangulation (points and lines are skipped by the walk; asking
// assimp to remove them makes it fail on files that have nothing else): no
// aiProcess_JoinIdenticalVertices (slow, and it compares normals: the engine welds by position
// itself) and no aiProcess_FindDegenerates (its area threshold is absolute and deletes whole
// small meshes). Before post-processing reads the scene, it is checked here: assimp's own
// passes would trip over a missing mesh or a face index past its mesh.
#include "assimp_reader.hpp"

#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <algorithm>
#include <new>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "base/errors.hpp"
#include "input_file.hpp"
#include "raw_scene.hpp"

namespace tumble::engine::detail {
namespace {

/// One line of assimp's error text.
std::string one_line(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  while (!text.empty() && (text.back() == ' ' || text.back() == '\r')) text.pop_back();
  return text;
}

/// Checks the scene as assimp read it, before any post-processing reads it too: every mesh
/// present, with positions, and every face index inside its mesh. Returns the count of faces
/// that have any corner (assimp leaves empty faces where an OFF file ran short).
std::uint64_t validate_scene(const aiScene& scene, const std::string& file) {
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

/// The nodes below the root, numbered in the order they are first met (a node met again keeps
/// its number); null children become kMissingNode when written.
std::vector<const aiNode*> number_nodes(const aiNode& root,
                                        std::unordered_map<const aiNode*, std::uint32_t>& number) {
  std::vector<const aiNode*> nodes{&root};
  number.emplace(&root, 0);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const aiNode& node = *nodes[i];
    for (unsigned c = 0; c < node.mNumChildren; ++c) {
      const aiNode* const child = node.mChildren == nullptr ? nullptr : node.mChildren[c];
      if (child == nullptr || number.contains(child)) continue;
      number.emplace(child, static_cast<std::uint32_t>(nodes.size()));
      nodes.push_back(child);
    }
  }
  return nodes;
}

void write_node(AnswerWriter& out, const aiNode& node,
                const std::unordered_map<const aiNode*, std::uint32_t>& number) {
  out.value(static_cast<std::uint32_t>(node.mName.length));
  out.bytes(node.mName.C_Str(), node.mName.length);
  out.align(4);
  const aiMatrix4x4& m = node.mTransformation;
  const float transform[16] = {m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4,
                               m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3, m.d4};
  out.bytes(transform, sizeof transform);
  const unsigned meshes = node.mMeshes == nullptr ? 0 : node.mNumMeshes;
  out.value(static_cast<std::uint32_t>(meshes));
  out.bytes(node.mMeshes, meshes * sizeof(std::uint32_t));
  out.value(static_cast<std::uint32_t>(node.mNumChildren));
  for (unsigned c = 0; c < node.mNumChildren; ++c) {
    const aiNode* const child = node.mChildren == nullptr ? nullptr : node.mChildren[c];
    out.value(child == nullptr ? kMissingNode : number.at(child));
  }
}

void write_mesh(AnswerWriter& out, const aiMesh& mesh) {
  static_assert(sizeof(ai_real) == sizeof(float), "assimp built with double precision");
  out.value(static_cast<std::uint32_t>(mesh.mPrimitiveTypes));
  out.value(static_cast<std::uint32_t>(mesh.mNumVertices));
  out.bytes(mesh.mVertices, std::size_t{mesh.mNumVertices} * sizeof(aiVector3D));
  out.value(static_cast<std::uint32_t>(mesh.mNumFaces));
  const bool all_triangles = std::all_of(mesh.mFaces, mesh.mFaces + mesh.mNumFaces,
                                         [](const aiFace& face) { return face.mNumIndices == 3; });
  out.value(std::uint32_t{all_triangles ? 1u : 0u});
  if (!all_triangles) {
    for (unsigned f = 0; f < mesh.mNumFaces; ++f)
      out.value(std::uint32_t{mesh.mFaces[f].mNumIndices});
  }
  for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
    const aiFace& face = mesh.mFaces[f];
    out.bytes(face.mIndices, std::size_t{face.mNumIndices} * sizeof(std::uint32_t));
  }
}

/// Writes the checked, triangulated scene.
void write_scene(AnswerWriter& out, const aiScene& scene, std::uint64_t faces_read,
                 bool skeleton_only) {
  std::unordered_map<const aiNode*, std::uint32_t> number;
  const std::vector<const aiNode*> nodes = number_nodes(*scene.mRootNode, number);
  out.value(kRawSceneMagic);
  out.value(kRawSceneVersion);
  out.value(faces_read);
  out.value(std::uint32_t{skeleton_only ? kRawSkeletonOnly : 0u});
  out.value(static_cast<std::uint32_t>(nodes.size()));
  out.value(static_cast<std::uint32_t>(scene.mNumMeshes));
  for (const aiNode* node : nodes) write_node(out, *node, number);
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) write_mesh(out, *scene.mMeshes[m]);
}

}  // namespace

void read_with_assimp(const std::vector<std::string>& request, AnswerWriter& out) {
  // request: the path to open, the file's name as the user gave it (for messages).
  const std::string& path = request.at(0);
  const std::string& name = request.at(1);
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(path, 0);
  std::uint64_t faces_read = 0;
  bool skeleton_only = false;
  if (scene != nullptr) {
    faces_read = validate_scene(*scene, name);
    skeleton_only = only_skeleton_placeholders(*scene);
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
    if (scene != nullptr) validate_scene(*scene, name);
  }
  if (scene == nullptr) {
    const std::string reason = one_line(importer.GetErrorString());
    // assimp catches the allocation failure the memory limit causes: pass it on as such.
    if (reason.find("bad_alloc") != std::string::npos) throw std::bad_alloc();
    if (reason.find("No suitable reader") != std::string::npos) {
      fail(name, "unknown or unsupported mesh format");
    }
    fail(name, "cannot be read as a mesh (assimp: " + reason + ")");
  }
  write_scene(out, *scene, faces_read, skeleton_only);
}

}  // namespace tumble::engine::detail
