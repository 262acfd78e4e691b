#pragma once
// The 3D part of a frame: background gradient, optional ground with a soft shadow, shaded
// meshes and arrows (opaque, then translucent back to front), polylines and points.

#include <cstddef>
#include <vector>

#include "gl_program.hpp"
#include "gpu_mesh.hpp"
#include "render/draw_list.hpp"
#include "render/offscreen_context.hpp"

namespace tumble::render::detail {

class ScenePasses {
 public:
  /// Compiles the programs and builds the arrow shapes; needs the context current, also when
  /// it is destroyed (its members own the GL objects).
  /// `lod`: draw large meshes from their simplified copies where those are under a pixel off.
  explicit ScenePasses(bool lod = true);
  ScenePasses(const ScenePasses&) = delete;
  ScenePasses& operator=(const ScenePasses&) = delete;

  /// Draws everything but the overlays into the context's framebuffer. Throws
  /// std::invalid_argument for a MeshId this renderer never returned.
  void draw(const DrawList& frame, const std::vector<GpuMesh>& meshes, OffscreenContext& context);

  /// Triangles drawn into the image by the last draw() (shadow pass not counted).
  std::size_t last_frame_triangles() const { return triangles_; }

 private:
  /// One shaded solid (a mesh instance or half an arrow) of the current frame.
  struct Solid {
    const GpuMesh* mesh;
    Eigen::Matrix4f model;
    Rgba colour;
    float view_depth;       // distance along the view direction, to sort translucent solids
    std::size_t level = 0;  // level of detail drawn (GpuMesh::levels)
    float scale = 1.0f;     // largest axis scale of `model`
  };

  void collect_solids(const DrawList& frame, const std::vector<GpuMesh>& meshes,
                      const Eigen::Matrix4f& view, int height);
  void draw_shadow_map(const DrawList& frame);
  void draw_background(const SceneStyle& style);
  void draw_ground(const DrawList& frame, int height);
  void draw_solids(bool translucent);
  void draw_lines_and_points(const DrawList& frame, int width, int height);

  GlProgram background_program_;
  GlProgram mesh_program_;
  GlProgram shadow_program_;
  GlProgram ground_program_;
  GlProgram shadowed_ground_program_;
  GlProgram line_program_;
  GlProgram point_program_;
  GpuMesh cylinder_;
  GpuMesh cone_;
  GlVertexArray empty_vao_;
  GlVertexArray ground_vao_;
  GlBuffer ground_buffer_;
  GlVertexArray stream_vao_;
  GlBuffer stream_buffer_;
  GlTexture shadow_texture_;  // created with shadow_fbo_ by the first frame that casts shadows
  GlFramebuffer shadow_fbo_;

  // Per-frame state.
  std::vector<Solid> solids_;
  std::vector<float> stream_;
  Eigen::Matrix4f view_projection_ = Eigen::Matrix4f::Identity();
  Eigen::Matrix4f light_view_projection_ = Eigen::Matrix4f::Identity();
  Eigen::Vector3f scene_centre_ = Eigen::Vector3f::Zero();
  float scene_radius_ = 0.0f;
  bool shadow_valid_ = false;
  bool lod_ = true;
  std::size_t triangles_ = 0;
};

}  // namespace tumble::render::detail
