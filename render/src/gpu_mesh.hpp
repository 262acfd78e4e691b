#pragma once
// A mesh resident on the GPU: interleaved position + normal vertex buffer and its bounds. It
// owns its GL objects (move-only); destroy it with its context current.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <memory>
#include <vector>

#include "gl_handle.hpp"
#include "mesh_lod.hpp"
#include "render/draw_list.hpp"

namespace tumble::render::detail {

struct GpuMesh {
  GlVertexArray vao;
  GlBuffer vertex_buffer;
  GlBuffer index_buffer;  // none when the mesh was un-indexed for flat shading
  GLsizei count = 0;      // indices (or vertices) of the full mesh
  /// Level 0 is the full mesh; simplified copies follow (indexed meshes over
  /// kLodMinTriangles triangles only), their indices after the full mesh's in index_buffer,
  /// made as frames need them (refine_for).
  std::vector<LodLevel> levels;
  /// The chain still being made; empty once it is complete or without level of detail.
  std::unique_ptr<LodChain> chain;
  std::size_t index_capacity = 0;  ///< indices index_buffer holds room for
  Eigen::AlignedBox3f box;         // bounding box in the body frame
  float radius = 0.0f;             // bounding sphere about the box's centre
  bool closed = false;             // MeshData::closed: back faces are hidden from outside

  Eigen::Vector3f centre() const { return box.center(); }

  /// Makes (and uploads) the levels a frame drawn at `pixels_per_unit` pixels per mesh unit
  /// may pick (LodChain::grow_for); its context must be current.
  void refine_for(float pixels_per_unit);
  /// Draws level `level` (clamped to the coarsest there is).
  void draw(std::size_t level = 0) const;
  /// Triangles of level `level` (clamped likewise).
  std::size_t triangles(std::size_t level = 0) const;
};

/// Validates and uploads a mesh (throws std::invalid_argument naming what is wrong). Without
/// normals the triangles are un-indexed so each gets its own flat normal. `with_lod` prepares
/// the simplified copies of a large indexed mesh (made when a frame first needs them).
GpuMesh upload_mesh(const MeshData& mesh, bool with_lod = false);

}  // namespace tumble::render::detail
