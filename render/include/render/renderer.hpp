#pragma once
// Draws a DrawList off-screen (OSMesa llvmpipe, no GPU or display) and hands back the pixels.
//
// Design note
// - One OSMesa core-profile context per Renderer, rendering into its own FBO (multisampled when
//   asked; the sample count is clamped to what the driver accepts, never a black frame).
// - Anti-aliasing is either multisampling (`samples`) or a post-process filter (`filter`, FXAA
//   after Lottes 2009): the scene draws into a colour texture, a same-format blit copies it into
//   a second FBO, the scene read back once gives the 4x4 blocks where the filter's test passes
//   at some pixel (found on the CPU) and the filter runs only on those, so flat pixels stay bit
//   for bit; the overlay is drawn on the filtered image, so text is never blurred. On llvmpipe
//   the filter costs a fraction of 4x multisampling.
// - Meshes are uploaded once (upload() -> MeshId); a frame only sets uniforms and issues draws,
//   except polylines and points, which are streamed because they change every frame.
// - Pass order: vertical-gradient background (a full-screen triangle, so no clear colour to keep
//   in sync), ground plane, opaque meshes and arrows, polylines and points, translucent meshes
//   sorted back to front, then ImGui text and panels.
// - Level of detail (RendererOptions::lod): large meshes get a chain of simplified index
//   buffers over the same vertices, each with a bound on its distance to the full surface,
//   made as frames first need them; a frame draws the coarsest level whose bound, at the
//   mesh's nearest depth, is under a pixel, so the outline moves by less than a pixel.
//   Callers' data (mass properties) never change.
// - Static layers (RendererOptions::reuse_static_layers): the background and the ground outside
//   the shadow's patch depend only on the camera, the size and the style; they are drawn once,
//   stored (colour and depth) and copied back at the start of each frame that shares them.
// - Shading is per pixel: a key light (which also casts the shadow), a fill light mirrored about
//   the view direction and a hemisphere ambient, so a tumbling body never turns black.
// - Shadows: a 1024^2 depth map rendered from the key light (orthographic, fitted to the scene's
//   bounding sphere), received by the ground only and filtered with 2x2 hardware-compared
//   bilinear taps (PCF over a 4x4-texel footprint) for a soft edge. The shadow pass is skipped
//   when the ground is off. Bodies do not self-shadow, which keeps them free of shadow acne at
//   any scale.
// - Overlays use Dear ImGui's OpenGL3 backend compiled from Debian's shipped source against
//   OSMesa's prototypes (the core profile rules out the prebuilt OpenGL2 backend). The ImGui
//   context and font atlas are created on the first frame that has labels or panels.

#include <cstddef>
#include <functional>
#include <memory>

#include "base/image.hpp"
#include "render/draw_list.hpp"

namespace tumble::render {

/// A post-process anti-aliasing filter.
enum class AntialiasingFilter {
  none,  ///< aliased (or multisampled, with RendererOptions::samples)
  fxaa,  ///< edge-directed blend after Lottes' FXAA (2009): 1.05-1.3x the time of aliased
};

/// Image size and anti-aliasing of a Renderer.
struct RendererOptions {
  int width = 1280;
  int height = 720;
  /// Samples per pixel for anti-aliasing (1 = off, the fast default). Clamped to what the
  /// driver supports (4 on llvmpipe); 4x costs about 3x the time of 1x per frame on llvmpipe,
  /// mostly in the resolve, so it suits final renders rather than previews.
  int samples = 1;
  /// Level of detail: a mesh of more than 20,000 triangles also gets simplified copies
  /// (meshoptimizer), made when a frame first needs them, and each frame draws the coarsest
  /// whose surface lies under a pixel from the full mesh's at the size it is drawn. false:
  /// always the full mesh.
  bool lod = true;
  /// Post-process anti-aliasing of the 3D scene (not the overlay). Ignored when multisampling
  /// is in use (samples > 1 after clamping). Off by default here, so golden images stay
  /// aliased; `tumble render` and `tumble compare` choose fxaa unless told otherwise.
  AntialiasingFilter filter = AntialiasingFilter::none;
  /// While the camera, the image size and the scene style stay from one frame to the next,
  /// start each frame from a stored copy (colour and depth) of the background and the
  /// unshadowed ground instead of drawing them again. The image is the same pixel for pixel;
  /// false draws every layer every frame (for comparisons).
  bool reuse_static_layers = true;
  /// The anti-aliasing filter reads back and scans only the box where anything but the
  /// background was drawn (the background gradient has no edge to filter), unless a ground is
  /// shown or something reaches behind the camera. The image is the same pixel for pixel;
  /// false scans the whole frame (for comparisons).
  bool filter_drawn_region = true;
};

/// Drawing a caller adds on top of a frame (the viewer's interactive ImGui panels).
struct ExtraPass {
  /// Called with the renderer's GL context current and the frame's framebuffer bound, after
  /// every pass of the frame and before the pixels are read back; gets the frame's size.
  std::function<void(int width, int height)> draw;
  /// When set, receives the frame as it was before `draw` (what `tumble render` writes).
  Image* before = nullptr;
};

/// Off-screen renderer; not thread-safe, use one per thread.
class Renderer {
 public:
  /// Creates the GL context. Throws std::runtime_error (one line) when it can't (a GL or
  /// OSMesa failure, never a tumble::InputError), std::invalid_argument for an invalid size.
  explicit Renderer(const RendererOptions& options = {});
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// Uploads a mesh once; the handle is valid for this renderer's lifetime. Throws
  /// std::invalid_argument for malformed meshes.
  MeshId upload(const MeshData& mesh);

  /// Meshes uploaded so far (the next upload's handle value).
  std::size_t mesh_count() const;
  /// Releases every mesh uploaded after the first `keep` (their GL objects are deleted and their
  /// handles become invalid): a caller that rebuilds its scene takes mesh_count() once and
  /// releases back to it.
  void release_meshes(std::size_t keep);

  /// Draws one frame and returns its pixels (rows top-down).
  Image render(const DrawList& frame);
  /// Same, reusing `out`'s storage (no allocation once sized).
  void render(const DrawList& frame, Image& out);

  /// Same, then `extra.draw` on top; `out` gets the frame with it.
  void render(const DrawList& frame, Image& out, const ExtraPass& extra);

  /// Runs `work` with this renderer's GL context current (for callers that create or release
  /// GL objects of their own, such as an ImGui backend, in this context).
  void with_context(const std::function<void()>& work);

  /// Draws later frames at `width` x `height` (the viewer's window was resized): the
  /// framebuffers (and the post-process's) are made again at that size in the same context, so
  /// uploaded meshes stay valid; the projection's aspect follows the new size. Throws
  /// std::invalid_argument for a size outside 1..16384 and std::runtime_error when the new
  /// framebuffers cannot be made (the renderer then keeps its old size).
  void resize(int width, int height);

  int width() const;
  int height() const;
  /// Samples per pixel actually used.
  int samples() const;
  /// Triangles the last frame drew into the image (after the level of detail's choice; the
  /// shadow pass not counted).
  std::size_t last_frame_triangles() const;
  /// The post-process filter actually used (none when multisampling).
  AntialiasingFilter filter() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tumble::render
