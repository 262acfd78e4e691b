#pragma once
// The 3D part of a frame: background gradient, optional ground with a soft shadow, shaded
// meshes and arrows (opaque, then translucent back to front), polylines and points.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "fxaa_blocks.hpp"
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
  /// `reuse_static_layers`: while the camera, size and style stay, start each frame from a
  /// stored copy of the background and unshadowed ground (colour and depth) instead of
  /// drawing them again; the image is the same pixel for pixel.
  /// `smooth_lines`: polylines get their edge pixels' coverage as alpha (anti-aliased lines).
  explicit ScenePasses(bool lod = true, bool reuse_static_layers = true, bool smooth_lines = false);
  ScenePasses(const ScenePasses&) = delete;
  ScenePasses& operator=(const ScenePasses&) = delete;

  /// Draws everything but the overlays into the context's framebuffer. Throws
  /// std::invalid_argument for a MeshId this renderer never returned.
  void draw(const DrawList& frame, std::vector<GpuMesh>& meshes, OffscreenContext& context);

  /// Where the last draw() put anything but the background: a box holding every solid's
  /// projected bounding box and every line and point with its width, grown by 8 pixels and out
  /// to whole 8-pixel blocks; outside it the frame is the background gradient alone, which the
  /// anti-aliasing filter leaves as it is. Empty when that cannot be bounded (a ground, or
  /// something reaching behind the camera): then the whole frame counts.
  const std::optional<PixelBox>& drawn_box() const { return drawn_; }

  /// Says that something other than draw() drew into the scene FBO after the last draw() (the
  /// overlay, without a post-process): the next frame restores all of the stored layers.
  void drawn_over() { written_.reset(); }

  /// Non-zero when the last draw() started from the stored layers: their generation (a new one
  /// each time they are stored), so that equal values mean the same pixels outside drawn_box().
  std::uint64_t started_from_layers() const { return frame_layers_; }

  /// Triangles drawn into the image by the last draw() (shadow pass not counted).
  std::size_t last_frame_triangles() const { return triangles_; }

 private:
  /// One shaded solid (a mesh instance or half an arrow) of the current frame.
  struct Solid {
    GpuMesh* mesh;
    Eigen::Matrix4f model;
    Rgba colour;
    float view_depth;       // distance along the view direction, to sort translucent solids
    std::size_t level = 0;  // level of detail drawn (GpuMesh::levels)
    float scale = 1.0f;     // largest axis scale of `model`
  };

  /// Where the ground goes this frame: the whole square, and the patch a shadow can reach.
  struct GroundPlacement {
    Eigen::Vector3f centre;
    float half_size;
    Eigen::Vector3f axis_u;
    Eigen::Vector3f axis_v;
    bool patch;  // the patch is drawn with the shadowed program, the rest without
    Eigen::Vector3f patch_centre;
    float patch_half_size;
  };

  std::optional<PixelBox> find_drawn_box(const DrawList& frame, int width, int height) const;
  void collect_solids(const DrawList& frame, std::vector<GpuMesh>& meshes,
                      const Eigen::Matrix4f& view, int height);
  void draw_shadow_map(const DrawList& frame);
  void draw_background(const SceneStyle& style);
  GroundPlacement place_ground(const DrawList& frame) const;
  /// Part 0: the shadowed patch (when placed); part 1: the rest of the ground, behind the patch.
  void draw_ground_part(const DrawList& frame, const GroundPlacement& ground, int part, int height);
  /// The layers that do not move (background, the ground outside the shadow's patch): restored
  /// from the stored copy when this frame's key matches it, else drawn and stored. False when
  /// they cannot be stored (reuse off, or the whole ground shadowed): draw() draws them itself.
  bool static_layers(const DrawList& frame, const GroundPlacement& ground,
                     OffscreenContext& context);
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
  float near_plane_ = 0.0f;  // this frame's camera's
  Eigen::Vector3f scene_centre_ = Eigen::Vector3f::Zero();
  float scene_radius_ = 0.0f;
  bool shadow_valid_ = false;
  bool lod_ = true;
  bool reuse_static_layers_ = true;
  bool smooth_lines_ = false;
  std::vector<float> static_key_;         // what the static layers depend on, this frame
  std::vector<float> stored_static_key_;  // and when they were stored (empty: nothing stored)
  std::vector<float> last_static_key_;    // the last frame's (stored only on a repeat)
  std::size_t triangles_ = 0;
  std::optional<PixelBox> drawn_;  // drawn_box()
  /// Where the scene FBO holds anything but the stored layers (outside it, it holds them):
  /// the last frame's drawn box, when it started from them. Empty: unknown, restore them all.
  std::optional<PixelBox> written_;
  std::uint64_t layers_generation_ = 0;  // stores so far
  std::uint64_t frame_layers_ = 0;       // started_from_layers()
};

}  // namespace tumble::render::detail
