#include "render/offscreen_context.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "gl.hpp"

namespace tumble::render {

struct OffscreenContext::Impl {
  OSMesaContext context = nullptr;
  std::uint8_t dummy_buffer[4 * 4 * 4] = {};  // the default framebuffer is never drawn to
  GLuint draw_fbo = 0;     // what the passes render into (multisampled when samples > 1)
  GLuint resolve_fbo = 0;  // single-sampled copy read back when drawing is multisampled
  GLuint renderbuffers[3] = {};
  std::vector<std::uint8_t> bottom_up;  // glReadPixels rows, flipped into the Image
};

namespace {

/// Creates colour + depth renderbuffers attached to a new FBO; returns whether it is complete.
bool make_framebuffer(int width, int height, int samples, GLuint& fbo, GLuint* colour,
                      GLuint* depth) {
  glGenFramebuffers(1, &fbo);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glGenRenderbuffers(1, colour);
  glBindRenderbuffer(GL_RENDERBUFFER, *colour);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples > 1 ? samples : 0, GL_RGBA8, width,
                                   height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, *colour);
  if (depth != nullptr) {
    glGenRenderbuffers(1, depth);
    glBindRenderbuffer(GL_RENDERBUFFER, *depth);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples > 1 ? samples : 0,
                                     GL_DEPTH_COMPONENT24, width, height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, *depth);
  }
  const bool complete = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE &&
                        glGetError() == GL_NO_ERROR;
  if (!complete) {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fbo);
    glDeleteRenderbuffers(1, colour);
    if (depth != nullptr) glDeleteRenderbuffers(1, depth);
    fbo = 0;
  }
  return complete;
}

}  // namespace

OffscreenContext::OffscreenContext(int width, int height, int samples)
    : impl_(std::make_unique<Impl>()), width_(width), height_(height) {
  if (width <= 0 || height <= 0 || width > 16384 || height > 16384) {
    throw std::runtime_error("offscreen context: invalid image size " + std::to_string(width) +
                             "x" + std::to_string(height));
  }
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
  impl_->context = OSMesaCreateContextAttribs(attributes, nullptr);
  if (impl_->context == nullptr) {
    throw std::runtime_error(
        "offscreen context: OSMesaCreateContextAttribs failed to create an OpenGL 3.3 core "
        "context (is libOSMesa with llvmpipe installed?)");
  }
  if (!OSMesaMakeCurrent(impl_->context, impl_->dummy_buffer, GL_UNSIGNED_BYTE, 4, 4)) {
    OSMesaDestroyContext(impl_->context);
    throw std::runtime_error("offscreen context: OSMesaMakeCurrent failed");
  }

  // Multisampled draw FBO: clamp to GL_MAX_SAMPLES, halve until complete (never black frames).
  GLint max_samples = 1;
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  int wanted = std::clamp(samples, 1, std::max(1, static_cast<int>(max_samples)));
  while (wanted > 1 && !make_framebuffer(width, height, wanted, impl_->draw_fbo,
                                         &impl_->renderbuffers[0], &impl_->renderbuffers[1])) {
    wanted /= 2;
  }
  if (wanted > 1) {
    if (!make_framebuffer(width, height, 1, impl_->resolve_fbo, &impl_->renderbuffers[2],
                          nullptr)) {
      OSMesaDestroyContext(impl_->context);
      throw std::runtime_error("offscreen context: resolve framebuffer is incomplete");
    }
  } else if (!make_framebuffer(width, height, 1, impl_->draw_fbo, &impl_->renderbuffers[0],
                               &impl_->renderbuffers[1])) {
    OSMesaDestroyContext(impl_->context);
    throw std::runtime_error("offscreen context: framebuffer " + std::to_string(width) + "x" +
                             std::to_string(height) + " is incomplete");
  }
  samples_ = wanted;
  glBindFramebuffer(GL_FRAMEBUFFER, impl_->draw_fbo);
  glViewport(0, 0, width, height);
}

OffscreenContext::~OffscreenContext() {
  if (impl_->context == nullptr) return;
  make_current();
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (impl_->resolve_fbo != 0) glDeleteFramebuffers(1, &impl_->resolve_fbo);
  glDeleteFramebuffers(1, &impl_->draw_fbo);
  glDeleteRenderbuffers(3, impl_->renderbuffers);
  OSMesaDestroyContext(impl_->context);
}

void OffscreenContext::make_current() {
  if (OSMesaGetCurrentContext() != impl_->context) {
    OSMesaMakeCurrent(impl_->context, impl_->dummy_buffer, GL_UNSIGNED_BYTE, 4, 4);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, impl_->draw_fbo);
  glViewport(0, 0, width_, height_);
}

void OffscreenContext::read_pixels(Image& out) {
  make_current();
  // Resolve the multisampled buffer into the single-sampled one.
  GLuint read_fbo = impl_->draw_fbo;
  if (impl_->resolve_fbo != 0) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, impl_->draw_fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, impl_->resolve_fbo);
    glBlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT,
                      GL_NEAREST);
    read_fbo = impl_->resolve_fbo;
  }
  // Read bottom-up rows and flip them into top-down order.
  const std::size_t row = 4 * static_cast<std::size_t>(width_);
  const std::size_t total = row * static_cast<std::size_t>(height_);
  impl_->bottom_up.resize(total);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, read_fbo);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, impl_->bottom_up.data());
  out.width = width_;
  out.height = height_;
  out.rgba.resize(total);
  for (int y = 0; y < height_; ++y) {
    std::memcpy(out.rgba.data() + row * static_cast<std::size_t>(y),
                impl_->bottom_up.data() + row * static_cast<std::size_t>(height_ - 1 - y), row);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, impl_->draw_fbo);
}

}  // namespace tumble::render
