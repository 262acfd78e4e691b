#pragma once
// Post-process anti-aliasing: filters the scene's colour texture into the output framebuffer
// (see fxaa_shaders.hpp for the filter), before the overlay is drawn so text stays crisp.
//
// Three steps a frame: read the scene back once and find, on the CPU, the 4x4-pixel blocks
// holding a pixel that passes the filter's contrast test (fxaa_blocks.hpp; the GPU pass of 25
// gathers per 8x8 block it replaces cost about a third of a light frame on llvmpipe), copy the
// scene into the output (a same-format blit, which llvmpipe does as a memory copy), then run
// the filter on those blocks only, one rectangle per run of blocks (flat blocks are not covered
// at all: llvmpipe runs a discarding fragment shader in full, per 4x4 block it touches).

#include <cstdint>
#include <optional>
#include <vector>

#include "fxaa_blocks.hpp"
#include "gl_handle.hpp"
#include "gl_program.hpp"

namespace tumble::render {
class OffscreenContext;
}

namespace tumble::render::detail {

class FxaaPass {
 public:
  /// Compiles the filter for `width` x `height` images; needs the context current.
  FxaaPass(int width, int height);

  /// Reads the context's scene (its framebuffer must be bound, as the scene passes leave it)
  /// and writes the filtered image into its output framebuffer, which stays the target of later
  /// draws (the overlay) and of the read-back. With `drawn`, only that box is read back and
  /// scanned (outside it the scene is the flat background, which the filter leaves alone).
  /// `copied`: the output already equals the scene outside these boxes (the last frame's
  /// drawn boxes over the same stored layers), so only they are copied; empty: the whole frame.
  void apply(OffscreenContext& context, const std::optional<PixelBox>& drawn = std::nullopt,
             const std::vector<PixelBox>* copied = nullptr);

  /// Edge blocks the last frame filtered.
  int last_edge_blocks() const { return edge_blocks_; }

 private:
  GlProgram filter_program_;
  GlVertexArray rectangles_;
  GlBuffer rectangle_buffer_;
  std::vector<std::uint8_t> scene_;  // the scene's pixels, bottom-up
  std::vector<BlockRun> runs_;
  std::vector<float> corners_;  // two triangles a run, in pixels
  int width_;
  int height_;
  int edge_blocks_ = 0;
};

}  // namespace tumble::render::detail
