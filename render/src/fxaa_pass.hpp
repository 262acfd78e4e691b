#pragma once
// Post-process anti-aliasing: filters the scene's colour texture into the output framebuffer
// (see fxaa_shaders.hpp for the filter), before the overlay is drawn so text stays crisp.
//
// Three steps a frame: copy the scene into the output (a same-format blit, which llvmpipe does
// as a memory copy), mark the 8x8-pixel blocks that hold an edge (a 1/64-size pass), then run
// the filter as one 8x8 point per marked block (flat blocks are not covered at all: llvmpipe
// would run a discarding fragment shader in full).

#include "gl_handle.hpp"
#include "gl_program.hpp"

namespace tumble::render {
class OffscreenContext;
}

namespace tumble::render::detail {

class FxaaPass {
 public:
  /// Compiles the filter and makes its block mask for `width` x `height` images; needs the
  /// context current. Throws std::runtime_error (one line) when the mask FBO is incomplete.
  FxaaPass(int width, int height);

  /// Reads the context's scene texture and writes the filtered image into its output
  /// framebuffer, which stays the target of later draws (the overlay) and of the read-back.
  void apply(OffscreenContext& context);

 private:
  GlProgram blocks_program_;
  GlProgram filter_program_;
  GlVertexArray empty_;  // core profile: a draw needs a vertex array, even with no attributes
  GlTexture blocks_;     // one texel per 8x8 pixels: 1 near an edge, else 0
  GlFramebuffer blocks_fbo_;
  int blocks_width_;
  int blocks_height_;
};

}  // namespace tumble::render::detail
