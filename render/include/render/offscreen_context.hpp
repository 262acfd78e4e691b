#pragma once
// An OSMesa (llvmpipe) OpenGL core-profile context rendering into a framebuffer object, with
// optional multisampling and top-down RGBA8 readback. No display or GPU needed.

#include <memory>

#include "render/image.hpp"

namespace tumble::render {

/// Owns the GL context and the FBO every pass draws into.
class OffscreenContext {
 public:
  /// Creates a core 3.3+ context and a width x height FBO with `samples` samples per pixel
  /// (1 = no MSAA; clamped to what the driver supports). Sets LP_NUM_THREADS=2 when unset.
  /// Throws std::invalid_argument for a size outside 1..16384 (the caller validates sizes) and
  /// std::runtime_error with one line when the context or FBO can't be created. The GL objects
  /// it owns are deleted with it, also when construction fails midway.
  OffscreenContext(int width, int height, int samples);
  ~OffscreenContext();
  OffscreenContext(const OffscreenContext&) = delete;
  OffscreenContext& operator=(const OffscreenContext&) = delete;

  /// Makes the context current on the calling thread and binds the draw FBO.
  void make_current();
  /// Resolves multisampling (if any) and reads the pixels back, row 0 at the top.
  void read_pixels(Image& out);

  int width() const { return width_; }
  int height() const { return height_; }
  /// Samples per pixel actually used (after clamping to GL_MAX_SAMPLES and completeness).
  int samples() const { return samples_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int width_;
  int height_;
  int samples_ = 1;
};

}  // namespace tumble::render
