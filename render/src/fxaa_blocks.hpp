#pragma once
// The FXAA filter's edge blocks, found on the CPU from the scene's pixels (fxaa_pass.cpp reads
// them back once; a GPU pass of 25 gathers per 8x8 block cost about a third of a light frame on
// llvmpipe, the read-back and this scan a few per cent).

#include <cstdint>
#include <vector>

namespace tumble::render::detail {

/// Pixels per side of an edge block.
inline constexpr int kEdgeBlock = 4;

/// A run of edge blocks in one block row: blocks [first, first + count) of row `row`.
struct BlockRun {
  int row = 0;
  int first = 0;
  int count = 0;
};

/// The runs of kEdgeBlock-sided blocks of an RGBA8 image (`width` x `height`, 4 bytes a pixel,
/// rows bottom-up as GL reads them) holding a pixel where the FXAA filter's contrast test can
/// pass: the green range over the pixel, its four sides and its up-right and down-left
/// diagonals (clamped to the image) at least 8 and at least (its brightest - 1) / 8, in 0..255.
/// The shader's test in floats is max(0.0312, 1/8 of the brightest), and 0.0312 * 255 = 7.96:
/// every pixel it filters passes (the second bound a rounding step looser), so every such pixel
/// is in a block. Every pixel is tested, a row at a time on its green bytes, in vector
/// operations. Runs come row by row, left to right, each as long as it can be; `runs` is
/// cleared first.
void find_edge_blocks(const std::uint8_t* rgba, int width, int height, std::vector<BlockRun>& runs);

/// A rectangle of pixels, GL's bottom-up coordinates: [x0, x1) x [y0, y1).
struct PixelBox {
  int x0 = 0;
  int y0 = 0;
  int x1 = 0;
  int y1 = 0;
};

/// Rectangles that cover exactly the union of `boxes` and do not overlap (empty boxes add
/// nothing): horizontal bands between the boxes' edges, each band's merged spans, and a band
/// joined to the one below while their spans are the same. For copies of a union of boxes,
/// each pixel once (the output copy's boxes, the last frame's and this one's, mostly overlap).
std::vector<PixelBox> disjoint_cover(const std::vector<PixelBox>& boxes);

}  // namespace tumble::render::detail
