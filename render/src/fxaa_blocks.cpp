#include "fxaa_blocks.hpp"

#include <algorithm>
#include <cstddef>
#include <utility>

namespace tumble::render::detail {

namespace {

/// The first, coarse scan's block side: a range over each block and its rim.
constexpr int kCoarseBlock = 8;

/// Whether a green range lo..hi (0..255) passes the block test: hi - lo >= max(0.0312 * 255,
/// lo / 8), kept in integers (0.0312 * 255 = 7.96, so a range of 8).
bool has_contrast(int lo, int hi) {
  return hi - lo >= 8 && 8 * (hi - lo) >= lo;
}

/// Green of pixel (x, y), clamped to the image (the filter's texture clamps to the edge).
int green(const std::uint8_t* rgba, int width, int height, int x, int y) {
  x = std::clamp(x, 0, width - 1);
  y = std::clamp(y, 0, height - 1);
  return rgba[4 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                   static_cast<std::size_t>(x)) +
              1];
}

/// Whether the filter's own test can pass at pixel (x, y): the green range over the pixel,
/// its four sides and two diagonals (up-right, down-left) against max(0.0312, hi / 8). A
/// rounding step looser than the shader's float test, so that every pixel it filters is kept.
bool pixel_passes(const std::uint8_t* rgba, int width, int height, int x, int y) {
  const int m = green(rgba, width, height, x, y);
  const int around[6] = {
      green(rgba, width, height, x, y + 1),     green(rgba, width, height, x + 1, y),
      green(rgba, width, height, x, y - 1),     green(rgba, width, height, x - 1, y),
      green(rgba, width, height, x + 1, y + 1), green(rgba, width, height, x - 1, y - 1)};
  int lo = m;
  int hi = m;
  for (int v : around) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  return hi - lo >= 7 && 8 * (hi - lo) >= hi - 1;
}

/// Whether any pixel of the kEdgeBlock-sided block (bx, by) passes the filter's test.
bool block_passes(const std::uint8_t* rgba, int width, int height, int bx, int by) {
  const int y1 = std::min(height, (by + 1) * kEdgeBlock);
  const int x1 = std::min(width, (bx + 1) * kEdgeBlock);
  for (int y = by * kEdgeBlock; y < y1; ++y) {
    for (int x = bx * kEdgeBlock; x < x1; ++x) {
      if (pixel_passes(rgba, width, height, x, y)) return true;
    }
  }
  return false;
}

}  // namespace

static void find_coarse_blocks(const std::uint8_t* rgba, int width, int height,
                               std::vector<BlockRun>& runs) {
  runs.clear();
  const int columns = (width + kCoarseBlock - 1) / kCoarseBlock;
  const int rows = (height + kCoarseBlock - 1) / kCoarseBlock;
  const std::size_t row_bytes = 4 * static_cast<std::size_t>(width);
  // Per pixel column, the byte-wise min and max over the block row's rows and its rim: every
  // channel at once (vectorises), of which only green is used.
  std::vector<std::uint8_t> low(row_bytes);
  std::vector<std::uint8_t> high(row_bytes);
  for (int by = 0; by < rows; ++by) {
    const int y0 = std::max(0, by * kCoarseBlock - 1);
    const int y1 = std::min(height, (by + 1) * kCoarseBlock + 1);
    const std::uint8_t* first = rgba + row_bytes * static_cast<std::size_t>(y0);
    std::copy(first, first + row_bytes, low.begin());
    std::copy(first, first + row_bytes, high.begin());
    for (int y = y0 + 1; y < y1; ++y) {
      const std::uint8_t* row = rgba + row_bytes * static_cast<std::size_t>(y);
      std::uint8_t* lo = low.data();
      std::uint8_t* hi = high.data();
      for (std::size_t i = 0; i < row_bytes; ++i) {
        lo[i] = std::min(lo[i], row[i]);
        hi[i] = std::max(hi[i], row[i]);
      }
    }
    int run_start = -1;
    for (int bx = 0; bx <= columns; ++bx) {
      bool edge = false;
      if (bx < columns) {
        const int x0 = std::max(0, bx * kCoarseBlock - 1);
        const int x1 = std::min(width, (bx + 1) * kCoarseBlock + 1);
        int lo = 255;
        int hi = 0;
        for (int x = x0; x < x1; ++x) {
          lo = std::min(lo, static_cast<int>(low[4 * static_cast<std::size_t>(x) + 1]));
          hi = std::max(hi, static_cast<int>(high[4 * static_cast<std::size_t>(x) + 1]));
        }
        edge = has_contrast(lo, hi);
      }
      if (edge && run_start < 0) run_start = bx;
      if (!edge && run_start >= 0) {
        runs.push_back({by, run_start, bx - run_start});
        run_start = -1;
      }
    }
  }
}

void find_edge_blocks(const std::uint8_t* rgba, int width, int height,
                      std::vector<BlockRun>& runs) {
  std::vector<BlockRun>& coarse = runs;  // refined into `fine`, then swapped back
  find_coarse_blocks(rgba, width, height, coarse);
  thread_local std::vector<BlockRun> fine;
  fine.clear();
  constexpr int kSplit = kCoarseBlock / kEdgeBlock;
  for (const BlockRun& run : coarse) {
    for (int sub = 0; sub < kSplit; ++sub) {
      const int by = run.row * kSplit + sub;
      if (by * kEdgeBlock >= height) break;
      const int end =
          std::min((run.first + run.count) * kSplit, (width + kEdgeBlock - 1) / kEdgeBlock);
      for (int bx = run.first * kSplit; bx < end; ++bx) {
        if (!block_passes(rgba, width, height, bx, by)) continue;
        if (!fine.empty() && fine.back().row == by && fine.back().first + fine.back().count == bx) {
          ++fine.back().count;
        } else {
          fine.push_back({by, bx, 1});
        }
      }
    }
  }
  // Sub-rows of one coarse row come interleaved by coarse run: sort by row, then column.
  std::sort(fine.begin(), fine.end(), [](const BlockRun& a, const BlockRun& b) {
    return a.row != b.row ? a.row < b.row : a.first < b.first;
  });
  runs.swap(fine);
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
