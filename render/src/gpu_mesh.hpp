#pragma once
// A mesh resident on the GPU: interleaved position + normal vertex buffer and its bounds. It
// owns its GL objects (move-only); destroy it with its context current.

#include <Eigen/Core>

#include "gl_handle.hpp"
#include "render/draw_list.hpp"

namespace tumble::render::detail {

struct GpuMesh {
  GlVertexArray vao;
  GlBuffer vertex_buffer;
  GlBuffer index_buffer;  // none when the mesh was un-indexed for flat shading
  GLsizei count = 0;      // indices (or vertices) to draw
  Eigen::Vector3f centre = Eigen::Vector3f::Zero();  // bounding sphere in the body frame
  float radius = 0.0f;

  void draw() const;
};

/// Validates and uploads a mesh (throws std::invalid_argument naming what is wrong). Without
/// normals the triangles are un-indexed so each gets its own flat normal.
GpuMesh upload_mesh(const MeshData& mesh);

}  // namespace tumble::render::detail
