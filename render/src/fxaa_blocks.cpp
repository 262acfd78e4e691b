#include "fxaa_blocks.hpp"

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstring>
#include <utility>

namespace tumble::render::detail {

namespace {

static_assert(kEdgeBlock == 4, "a block's marks are read as one 32-bit word");

/// Row `rgba`'s green bytes, the first and the last repeated once on either side (the filter's
/// texture clamps to the edge): out[0] .. out[width + 1]. A pixel is read as one 32-bit word,
/// green its second byte in memory, so that the loop vectorises.
void green_row(const std::uint8_t* __restrict rgba, std::size_t width,
               std::uint8_t* __restrict out) {
  for (std::size_t x = 0; x < width; ++x) {
    std::uint32_t pixel = 0;
    std::memcpy(&pixel, rgba + 4 * x, 4);
    out[x + 1] =
        static_cast<std::uint8_t>(pixel >> (std::endian::native == std::endian::little ? 8 : 16));
  }
  out[0] = out[1];
  out[width + 1] = out[width];
}

/// Sets marks[x] for each pixel x of a row that passes the test (see the header), given the
/// padded green rows below it, its own and above it. Bytes only, without branches: the
/// compiler turns it into 16-pixel vector operations (min, max, compare).
void mark_row(const std::uint8_t* __restrict below, const std::uint8_t* __restrict row,
              const std::uint8_t* __restrict above, std::size_t width,
              std::uint8_t* __restrict marks) {
  for (std::size_t x = 0; x < width; ++x) {
    const std::uint8_t m = row[x + 1], n = above[x + 1], e = row[x + 2], s = below[x + 1],
                       w = row[x], ne = above[x + 2], sw = below[x];
    const std::uint8_t lo =
        std::min(std::min(std::min(m, n), std::min(e, s)), std::min(std::min(w, ne), sw));
    const std::uint8_t hi =
        std::max(std::max(std::max(m, n), std::max(e, s)), std::max(std::max(w, ne), sw));
    const auto range = static_cast<std::uint8_t>(hi - lo);
    // 8 * range >= hi - 1 is range >= ceil((hi - 1) / 8): with hi = 8q + r, q + (r >= 2).
    const auto eighth = static_cast<std::uint8_t>((hi >> 3) + ((hi & 7) > 1 ? 1 : 0));
    marks[x] =
        static_cast<std::uint8_t>(marks[x] | (range >= std::max<std::uint8_t>(8, eighth) ? 1 : 0));
  }
}

}  // namespace

void find_edge_blocks(const std::uint8_t* rgba, int width, int height,
                      std::vector<BlockRun>& runs) {
  runs.clear();
  if (width <= 0 || height <= 0) return;
  const auto w = static_cast<std::size_t>(width);
  const std::size_t padded = w + 2;
  const std::size_t columns = (w + kEdgeBlock - 1) / kEdgeBlock;
  thread_local std::vector<std::uint8_t> scratch;
  scratch.assign(3 * padded + columns * kEdgeBlock, 0);
  // Rows y - 1, y and y + 1 (clamped to the image), then a block row's marks, a pixel row's
  // ORed together (zero past the last pixel).
  std::uint8_t* lines[3] = {scratch.data(), scratch.data() + padded, scratch.data() + 2 * padded};
  std::uint8_t* const marks = scratch.data() + 3 * padded;
  const std::size_t row_bytes = 4 * w;
  green_row(rgba, w, lines[1]);
  std::memcpy(lines[0], lines[1], padded);
  for (int y = 0; y < height; ++y) {
    if (y + 1 < height) {
      green_row(rgba + row_bytes * static_cast<std::size_t>(y + 1), w, lines[2]);
    } else {
      std::memcpy(lines[2], lines[1], padded);
    }
    mark_row(lines[0], lines[1], lines[2], w, marks);
    std::rotate(lines, lines + 1, lines + 3);
    if ((y + 1) % kEdgeBlock != 0 && y + 1 != height) continue;
    // The block row is complete: its runs of marked blocks.
    const int row = y / kEdgeBlock;
    int start = -1;
    for (std::size_t bx = 0; bx <= columns; ++bx) {
      std::uint32_t four = 0;
      if (bx < columns) std::memcpy(&four, marks + kEdgeBlock * bx, 4);
      if (four != 0 && start < 0) start = static_cast<int>(bx);
      if (four == 0 && start >= 0) {
        runs.push_back({row, start, static_cast<int>(bx) - start});
        start = -1;
      }
    }
    std::memset(marks, 0, columns * kEdgeBlock);
  }
}

std::vector<PixelBox> disjoint_cover(const std::vector<PixelBox>& boxes) {
  std::vector<int> edges;
  for (const PixelBox& box : boxes) {
    if (box.x0 < box.x1 && box.y0 < box.y1) edges.insert(edges.end(), {box.y0, box.y1});
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  std::vector<PixelBox> out;
  std::vector<std::pair<int, int>> spans, open_spans;  // this band's; those of `open`
  std::size_t open = 0;  // out[open..] are the rectangles still growing upward
  for (std::size_t band = 0; band + 1 < edges.size(); ++band) {
    const int y0 = edges[band], y1 = edges[band + 1];
    spans.clear();
    for (const PixelBox& box : boxes) {
      if (box.x0 < box.x1 && box.y0 <= y0 && y1 <= box.y1) spans.emplace_back(box.x0, box.x1);
    }
    std::sort(spans.begin(), spans.end());
    std::size_t merged = 0;
    for (const auto& span : spans) {
      if (merged > 0 && span.first <= spans[merged - 1].second) {
        spans[merged - 1].second = std::max(spans[merged - 1].second, span.second);
      } else {
        spans[merged++] = span;
      }
    }
    spans.resize(merged);
    if (!spans.empty() && spans == open_spans) {  // the band below holds the same spans
      for (std::size_t i = open; i < out.size(); ++i) out[i].y1 = y1;
      continue;
    }
    open = out.size();
    for (const auto& [x0, x1] : spans) out.push_back({x0, y0, x1, y1});
    open_spans = spans;
  }
  return out;
}

}  // namespace tumble::render::detail
