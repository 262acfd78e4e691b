#include "render/offscreen_context.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "gl_handle.hpp"

namespace tumble::render {

// The Impl's member types, in a named namespace: a type with internal linkage may not be a
// member's type of a class with external linkage.
namespace detail {

/// Owns an OSMesa context: destroyed after every GL object of the Impl (declared first).
struct OsmesaContextDeleter {
  void operator()(OSMesaContext context) const { OSMesaDestroyContext(context); }
};
using OsmesaContextPtr = std::unique_ptr<osmesa_context, OsmesaContextDeleter>;

/// A framebuffer object with a colour renderbuffer or texture and (optionally) a depth
/// renderbuffer.
struct OffscreenFramebuffer {
  detail::GlFramebuffer fbo;
  detail::GlRenderbuffer colour;
  detail::GlTexture texture;  // instead of `colour` when a post-process samples the image
  detail::GlRenderbuffer depth;
};

}  // namespace detail

namespace {

using detail::OsmesaContextPtr;
using Framebuffer = detail::OffscreenFramebuffer;

/// Attaches a single-sampled RGBA8 texture, bilinear and clamped to the edge, as the bound
/// FBO's colour (the scene renders into it and the post-process samples it).
detail::GlTexture attach_colour_texture(int width, int height) {
  detail::GlTexture texture = detail::GlTexture::create();
  glBindTexture(GL_TEXTURE_2D, texture.get());
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
  glBindTexture(GL_TEXTURE_2D, 0);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture.get(), 0);
  return texture;
}

/// Creates colour + depth renderbuffers attached to a new FBO; nothing (every object deleted
/// again) when it is incomplete. `as_texture` (single-sampled only) makes the colour a texture.
std::optional<Framebuffer> make_framebuffer(int width, int height, int samples, bool with_depth,
                                            bool as_texture = false) {
  Framebuffer made;
  made.fbo = detail::GlFramebuffer::create();
  glBindFramebuffer(GL_FRAMEBUFFER, made.fbo.get());
  if (as_texture) {
    made.texture = attach_colour_texture(width, height);
  } else {
    made.colour = detail::GlRenderbuffer::create();
    glBindRenderbuffer(GL_RENDERBUFFER, made.colour.get());
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples > 1 ? samples : 0, GL_RGBA8, width,
                                     height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                              made.colour.get());
  }
  if (with_depth) {
    made.depth = detail::GlRenderbuffer::create();
    glBindRenderbuffer(GL_RENDERBUFFER, made.depth.get());
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples > 1 ? samples : 0,
                                     GL_DEPTH_COMPONENT24, width, height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER,
                              made.depth.get());
  }
  const bool complete = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE &&
                        glGetError() == GL_NO_ERROR;
  if (!complete) {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return std::nullopt;
  }
  return made;
}

/// Throws std::invalid_argument for a size outside 1..16384.
void check_size(int width, int height) {
  if (width <= 0 || height <= 0 || width > 16384 || height > 16384) {
    throw std::invalid_argument("offscreen context: invalid image size " + std::to_string(width) +
                                "x" + std::to_string(height));
  }
}

}  // namespace

struct OffscreenContext::Impl {
  // Members go in reverse order: the GL objects first, the context that owns them last.
  detail::OsmesaContextPtr context;
  std::uint8_t dummy_buffer[4 * 4 * 4] = {};  // the default framebuffer is never drawn to
  detail::OffscreenFramebuffer draw;  // what the passes render into (multisampled when samples > 1)
  detail::OffscreenFramebuffer
      resolve;  // single-sampled copy read back when drawing is multisampled
  detail::OffscreenFramebuffer
      output;  // the post-process's result (draw's colour is then a texture)
  detail::OffscreenFramebuffer layers;  // a stored copy of draw's colour and depth, made lazily
  detail::OffscreenFramebuffer panels;  // stored boxes of the output's colour, made lazily
  std::vector<std::uint8_t> bottom_up;  // glReadPixels rows, flipped into the Image

  /// The FBO draws go to for `target`.
  GLuint fbo(Target target) const {
    return target == Target::output && output.fbo ? output.fbo.get() : draw.fbo.get();
  }
};

OffscreenContext::OffscreenContext(int width, int height, int samples, bool post_process)
    : impl_(std::make_unique<Impl>()), width_(width), height_(height) {
  check_size(width, height);
  // llvmpipe reads its thread count at context creation; 2 is fastest on this class of machine.
  ::setenv("LP_NUM_THREADS", "2", /*overwrite=*/0);

  // A core 3.3+ profile context.
  const int attributes[] = {OSMESA_FORMAT,
                            OSMESA_RGBA,
                            OSMESA_DEPTH_BITS,
                            0,
                            OSMESA_PROFILE,
                            OSMESA_CORE_PROFILE,
                            OSMESA_CONTEXT_MAJOR_VERSION,
                            3,
                            OSMESA_CONTEXT_MINOR_VERSION,
                            3,
                            0};
  // Every failure below leaves cleanup to impl_: its framebuffers go while the context is still
  // current, then the context.
  impl_->context.reset(OSMesaCreateContextAttribs(attributes, nullptr));
  if (impl_->context == nullptr) {
    throw std::runtime_error(
        "offscreen context: OSMesaCreateContextAttribs failed to create an OpenGL 3.3 core "
        "context (is libOSMesa with llvmpipe installed?)");
  }
  if (!OSMesaMakeCurrent(impl_->context.get(), impl_->dummy_buffer, GL_UNSIGNED_BYTE, 4, 4)) {
    throw std::runtime_error("offscreen context: OSMesaMakeCurrent failed");
  }

  GLint max_samples = 1;
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  samples_ = std::clamp(samples, 1, std::max(1, static_cast<int>(max_samples)));
  make_framebuffers(post_process);
}

void OffscreenContext::make_framebuffers(bool post_process) {
  // Multisampled draw FBO: halve the samples until it is complete (never black frames).
  int wanted = samples_;
  std::optional<Framebuffer> draw;
  while (wanted > 1 && !(draw = make_framebuffer(width_, height_, wanted, /*with_depth=*/true))) {
    wanted /= 2;
  }
  Framebuffer resolve;
  Framebuffer output;
  if (wanted > 1) {
    std::optional<Framebuffer> made = make_framebuffer(width_, height_, 1, /*with_depth=*/false);
    if (!made) throw std::runtime_error("offscreen context: resolve framebuffer is incomplete");
    resolve = std::move(*made);
  } else if (!(draw = make_framebuffer(width_, height_, 1, /*with_depth=*/true, post_process))) {
    throw std::runtime_error("offscreen context: framebuffer " + std::to_string(width_) + "x" +
                             std::to_string(height_) + " is incomplete");
  } else if (post_process) {
    std::optional<Framebuffer> made = make_framebuffer(width_, height_, 1, /*with_depth=*/false);
    if (!made) throw std::runtime_error("offscreen context: output framebuffer is incomplete");
    output = std::move(*made);
  }
  impl_->draw = std::move(*draw);
  impl_->resolve = std::move(resolve);
  impl_->output = std::move(output);
  impl_->layers = Framebuffer{};  // the old size's copies: made again by the next store
  impl_->panels = Framebuffer{};
  samples_ = wanted;
  glBindFramebuffer(GL_FRAMEBUFFER, impl_->fbo(target_));
  glViewport(0, 0, width_, height_);
}

void OffscreenContext::resize(int width, int height) {
  check_size(width, height);
  if (width == width_ && height == height_) return;
  make_current();
  const int old_width = std::exchange(width_, width);
  const int old_height = std::exchange(height_, height);
  try {
    make_framebuffers(has_post_process());
  } catch (...) {
    // The old framebuffers are still there: keep drawing at the old size.
    width_ = old_width;
    height_ = old_height;
    make_current();
    throw;
  }
}

OffscreenContext::~OffscreenContext() {
  if (impl_->context == nullptr) return;
  // impl_'s GL objects are deleted after this body, in this context.
  make_current();
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void OffscreenContext::make_current() {
  if (OSMesaGetCurrentContext() != impl_->context.get()) {
    OSMesaMakeCurrent(impl_->context.get(), impl_->dummy_buffer, GL_UNSIGNED_BYTE, 4, 4);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, impl_->fbo(target_));
  glViewport(0, 0, width_, height_);
}

unsigned int OffscreenContext::scene_texture() const {
  return impl_->draw.texture.get();
}

bool OffscreenContext::has_post_process() const {
  return static_cast<bool>(impl_->output.fbo);
}

void OffscreenContext::copy_scene_to_output() {
  copy_scene_box_to_output(0, 0, width_, height_);
}

bool OffscreenContext::store_scene() {
  make_current();
  if (!impl_->layers.fbo) {
    std::optional<Framebuffer> made =
        make_framebuffer(width_, height_, samples_, /*with_depth=*/true);
    if (!made) {
      make_current();
      return false;  // no copy: the caller draws every layer every frame
    }
    impl_->layers = std::move(*made);
  }
  copy_colour_and_depth(impl_->draw.fbo.get(), impl_->layers.fbo.get(), /*depth=*/true);
  return true;
}

bool OffscreenContext::has_stored_scene() const {
  return static_cast<bool>(impl_->layers.fbo);
}

void OffscreenContext::restore_scene(bool depth) {
  if (!impl_->layers.fbo) throw std::logic_error("offscreen context: no stored scene to restore");
  copy_colour_and_depth(impl_->layers.fbo.get(), impl_->draw.fbo.get(), depth);
  if (!depth) glClear(GL_DEPTH_BUFFER_BIT);  // llvmpipe marks its tiles cleared: no memory pass
}

namespace {

/// Copies `buffers` within a box (clamped to `width` x `height`) between two FBOs of the same
/// size, samples and formats: the same rectangle on both sides and no scissor, so Mesa copies
/// memory (a scissored blit would run a shader instead).
void copy_box(GLuint from, GLuint to, GLbitfield buffers, int width, int height, int x0, int y0,
              int x1, int y1) {
  x0 = std::clamp(x0, 0, width);
  x1 = std::clamp(x1, x0, width);
  y0 = std::clamp(y0, 0, height);
  y1 = std::clamp(y1, y0, height);
  if (x0 == x1 || y0 == y1) return;
  glBindFramebuffer(GL_READ_FRAMEBUFFER, from);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, to);
  glBlitFramebuffer(x0, y0, x1, y1, x0, y0, x1, y1, buffers, GL_NEAREST);
}

}  // namespace

void OffscreenContext::restore_scene_box(int x0, int y0, int x1, int y1) {
  if (!impl_->layers.fbo) throw std::logic_error("offscreen context: no stored scene to restore");
  // Copying the depth too costs less than clearing it: a clear reaches every tile of the frame.
  copy_box(impl_->layers.fbo.get(), impl_->draw.fbo.get(),
           GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT, width_, height_, x0, y0, x1, y1);
  glBindFramebuffer(GL_FRAMEBUFFER, impl_->fbo(target_));
}

void OffscreenContext::copy_scene_box_to_output(int x0, int y0, int x1, int y1) {
  if (!impl_->output.fbo) return;
  make_current();
  copy_box(impl_->draw.fbo.get(), impl_->output.fbo.get(), GL_COLOR_BUFFER_BIT, width_, height_, x0,
           y0, x1, y1);
  glBindFramebuffer(GL_FRAMEBUFFER, impl_->fbo(target_));
}

bool OffscreenContext::store_output_box(int x0, int y0, int x1, int y1) {
  if (!impl_->output.fbo) return false;
  make_current();
  if (!impl_->panels.fbo) {
    std::optional<Framebuffer> made = make_framebuffer(width_, height_, 1, /*with_depth=*/false);
    if (!made) {
      make_current();
      return false;
    }
    impl_->panels = std::move(*made);
  }
  copy_box(impl_->output.fbo.get(), impl_->panels.fbo.get(), GL_COLOR_BUFFER_BIT, width_, height_,
           x0, y0, x1, y1);
  glBindFramebuffer(GL_FRAMEBUFFER, impl_->fbo(target_));
  return true;
}

bool OffscreenContext::has_stored_output() const {
  return impl_->panels.fbo && impl_->output.fbo;
}

void OffscreenContext::restore_output_box(int x0, int y0, int x1, int y1) {
  if (!has_stored_output()) throw std::logic_error("offscreen context: no stored output boxes");
  copy_box(impl_->panels.fbo.get(), impl_->output.fbo.get(), GL_COLOR_BUFFER_BIT, width_, height_,
           x0, y0, x1, y1);
  glBindFramebuffer(GL_FRAMEBUFFER, impl_->fbo(target_));
}

void OffscreenContext::copy_colour_and_depth(unsigned int from, unsigned int to, bool depth) {
  // The depth values arrive bit for bit.
  copy_box(from, to, GL_COLOR_BUFFER_BIT | (depth ? GL_DEPTH_BUFFER_BIT : 0), width_, height_, 0, 0,
           width_, height_);
  glBindFramebuffer(GL_FRAMEBUFFER, impl_->fbo(target_));
}

void OffscreenContext::read_pixels(Image& out) {
  make_current();
  // Resolve the multisampled buffer into the single-sampled one.
  GLuint read_fbo = impl_->fbo(target_);
  if (impl_->resolve.fbo) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, impl_->draw.fbo.get());
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, impl_->resolve.fbo.get());
    glBlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT,
                      GL_NEAREST);
    read_fbo = impl_->resolve.fbo.get();
  }
  // GL rows are bottom-up. Mesa's GL_MESA_pack_invert makes glReadPixels write them top-down
  // straight into the image (no second buffer, no flipping copy); without it, read bottom-up
  // and flip.
  const std::size_t row = 4 * static_cast<std::size_t>(width_);
  const std::size_t total = row * static_cast<std::size_t>(height_);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, read_fbo);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  out.width = width_;
  out.height = height_;
  out.rgba.resize(total);
  while (glGetError() != GL_NO_ERROR) {
  }
  glPixelStorei(GL_PACK_INVERT_MESA, GL_TRUE);
  if (glGetError() == GL_NO_ERROR) {
    glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, out.rgba.data());
    glPixelStorei(GL_PACK_INVERT_MESA, GL_FALSE);
  } else {
    impl_->bottom_up.resize(total);
    glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, impl_->bottom_up.data());
    for (int y = 0; y < height_; ++y) {
      std::memcpy(out.rgba.data() + row * static_cast<std::size_t>(y),
                  impl_->bottom_up.data() + row * static_cast<std::size_t>(height_ - 1 - y), row);
    }
  }
  glBindFramebuffer(GL_FRAMEBUFFER, impl_->fbo(target_));
}

}  // namespace tumble::render
