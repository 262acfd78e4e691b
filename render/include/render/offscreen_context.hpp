#pragma once
// An OSMesa (llvmpipe) OpenGL core-profile context rendering into a framebuffer object, with
// optional multisampling or a colour texture for a post-process, and top-down RGBA8 readback.
// No display or GPU needed.

#include <memory>

#include "base/image.hpp"

namespace tumble::render {

/// Owns the GL context and the FBO every pass draws into.
class OffscreenContext {
 public:
  /// Creates a core 3.3+ context and a width x height FBO with `samples` samples per pixel
  /// (1 = no MSAA; clamped to what the driver supports). Sets LP_NUM_THREADS=2 when unset.
  /// Throws std::invalid_argument for a size outside 1..16384 (the caller validates sizes) and
  /// std::runtime_error with one line when the context or FBO can't be created. The GL objects
  /// it owns are deleted with it, also when construction fails midway.
  ///
  /// With `post_process` (and no multisampling after clamping) the scene FBO's colour is a
  /// texture (scene_texture()) and a second, depth-less FBO of the same size (the output)
  /// receives the post-processed image; set_target() chooses which one draws go to.
  OffscreenContext(int width, int height, int samples, bool post_process = false);
  ~OffscreenContext();
  OffscreenContext(const OffscreenContext&) = delete;
  OffscreenContext& operator=(const OffscreenContext&) = delete;

  /// Which framebuffer make_current() binds and read_pixels() reads.
  enum class Target {
    scene,   ///< the FBO the scene passes draw into (with depth)
    output,  ///< the post-process's output (the scene FBO when there is no post-process)
  };

  /// Makes the context current on the calling thread and binds the target FBO.
  void make_current();
  /// Sets the target of later make_current() and read_pixels() calls (scene at creation).
  void set_target(Target target) { target_ = target; }
  /// Resolves multisampling (if any) and reads the target's pixels back, row 0 at the top.
  void read_pixels(Image& out);

  /// Replaces the framebuffers with `width` x `height` ones (same samples, same post-process),
  /// in the same GL context, so uploaded meshes and programs stay. Throws like the constructor;
  /// on a failure the old size and framebuffers stay.
  void resize(int width, int height);

  /// The scene FBO's colour texture (0 without a post-process).
  unsigned int scene_texture() const;
  /// True when there is a separate output FBO for a post-process.
  bool has_post_process() const;
  /// Copies the scene FBO's colour into the output FBO (same size and format: a plain copy);
  /// leaves the target's FBO bound. Nothing without a post-process.
  void copy_scene_to_output();
  /// The same within [x0, x1) x [y0, y1) (GL's pixel coordinates) only.
  void copy_scene_box_to_output(int x0, int y0, int x1, int y1);

  /// Stores a copy of the scene FBO's colour and depth (the layers that stay from frame to
  /// frame: background, ground), in an FBO of the same size, samples and formats made on the
  /// first call. False (nothing stored) when that FBO cannot be made. Leaves the target bound.
  bool store_scene();
  /// True when store_scene() stored a copy since the framebuffers were last made.
  bool has_stored_scene() const;
  /// Copies the stored colour and depth back into the scene FBO, bit for bit; with `depth`
  /// false, only the colour, and the depth is cleared instead (for stored layers that wrote no
  /// depth). Throws std::logic_error when nothing is stored (a resize drops the stored copy).
  void restore_scene(bool depth = true);
  /// As restore_scene(), but copies colour and depth only within [x0, x1) x [y0, y1) (GL's
  /// pixel coordinates, row 0 at the bottom): for a scene FBO drawn over only there since the
  /// stored copy was last restored or made.
  void restore_scene_box(int x0, int y0, int x1, int y1);

  /// Copies the output FBO's colour within [x0, x1) x [y0, y1) (GL's pixel coordinates) into
  /// a stored copy of the output's size, made on the first call (the overlay's panels drawn
  /// over the stored layers). False, nothing stored, without a post-process or when that copy
  /// cannot be made. Leaves the target bound.
  bool store_output_box(int x0, int y0, int x1, int y1);
  /// True when store_output_box() stored a copy since the framebuffers were last made.
  bool has_stored_output() const;
  /// Copies that box back from the stored copy into the output FBO. Throws std::logic_error
  /// when nothing is stored.
  void restore_output_box(int x0, int y0, int x1, int y1);

  int width() const { return width_; }
  int height() const { return height_; }
  /// Samples per pixel actually used (after clamping to GL_MAX_SAMPLES and completeness).
  int samples() const { return samples_; }

 private:
  /// (Re)creates the framebuffers at width_ x height_ with up to samples_ samples.
  void make_framebuffers(bool post_process);
  /// Blits colour (and depth) between two FBOs of this context's size; leaves the target bound.
  void copy_colour_and_depth(unsigned int from, unsigned int to, bool depth);

  struct Impl;
  std::unique_ptr<Impl> impl_;
  int width_;
  int height_;
  int samples_ = 1;
  Target target_ = Target::scene;
};

}  // namespace tumble::render
