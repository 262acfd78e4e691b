// The FXAA edge blocks found on the CPU against a brute-force oracle: the filter's own test,
// in floats as the shader computes it, at every pixel. Every pixel the filter could change
// must lie in a returned block (else it would stay aliased), and blocks without such a pixel
// must be rare (each one costs llvmpipe a block of shading).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "fxaa_blocks.hpp"

namespace tumble::render::detail {
namespace {

constexpr int kBlocksWidth = 203;  // not a multiple of the block sides: partial blocks at the edges
constexpr int kBlocksHeight = 97;

float green_at(const std::vector<std::uint8_t>& rgba, int x, int y) {
  x = std::clamp(x, 0, kBlocksWidth - 1);
  y = std::clamp(y, 0, kBlocksHeight - 1);
  return static_cast<float>(rgba[4 * (y * kBlocksWidth + x) + 1]) / 255.0f;
}

/// The shader's test (fxaa_shaders.hpp): not discarded.
bool shader_filters(const std::vector<std::uint8_t>& rgba, int x, int y) {
  const float v[7] = {green_at(rgba, x, y),        green_at(rgba, x, y + 1),
                      green_at(rgba, x + 1, y),    green_at(rgba, x, y - 1),
                      green_at(rgba, x - 1, y),    green_at(rgba, x + 1, y + 1),
                      green_at(rgba, x - 1, y - 1)};
  const float lo = *std::min_element(v, v + 7);
  const float hi = *std::max_element(v, v + 7);
  return !(hi - lo < std::max(0.0312f, hi * 0.125f));
}

std::set<std::pair<int, int>> covered_blocks(const std::vector<std::uint8_t>& rgba) {
  std::vector<BlockRun> runs;
  find_edge_blocks(rgba.data(), kBlocksWidth, kBlocksHeight, runs);
  std::set<std::pair<int, int>> blocks;
  for (const BlockRun& run : runs) {
    for (int i = 0; i < run.count; ++i) blocks.insert({run.first + i, run.row});
  }
  return blocks;
}

/// A flat image with a dark disc, a faint ramp and noise in one corner.
std::vector<std::uint8_t> test_image(std::uint32_t seed) {
  std::vector<std::uint8_t> rgba(4 * kBlocksWidth * kBlocksHeight, 255);
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> noise(0, 40);
  for (int y = 0; y < kBlocksHeight; ++y) {
    for (int x = 0; x < kBlocksWidth; ++x) {
      int g = 180 + x / 40;  // gentle gradient: below the threshold
      if (std::hypot(x - 90.0, y - 50.0) < 30.0) g = 20 + x / 10;
      if (x > 170 && y > 70) g = 100 + noise(random);
      std::uint8_t* p = &rgba[4 * (y * kBlocksWidth + x)];
      p[0] = static_cast<std::uint8_t>(255 - g);
      p[1] = static_cast<std::uint8_t>(g);
      p[2] = static_cast<std::uint8_t>(g / 2);
    }
  }
  return rgba;
}

TEST(FxaaBlocks, EveryFilteredPixelIsInABlock) {
  for (std::uint32_t seed = 1; seed <= 3; ++seed) {
    const std::vector<std::uint8_t> rgba = test_image(seed);
    const auto blocks = covered_blocks(rgba);
    int filtered = 0;
    std::set<std::pair<int, int>> needed;
    for (int y = 0; y < kBlocksHeight; ++y) {
      for (int x = 0; x < kBlocksWidth; ++x) {
        if (!shader_filters(rgba, x, y)) continue;
        ++filtered;
        needed.insert({x / kEdgeBlock, y / kEdgeBlock});
        EXPECT_EQ(blocks.count({x / kEdgeBlock, y / kEdgeBlock}), 1u) << x << "," << y;
      }
    }
    EXPECT_GT(filtered, 200);  // the disc's rim and the noise
    // Only blocks with a filtered pixel, up to rounding ties of the integer test.
    EXPECT_LE(blocks.size(), needed.size() + needed.size() / 20) << "seed " << seed;
  }
}

TEST(FxaaBlocks, FlatAndFaintImagesHaveNone) {
  std::vector<std::uint8_t> rgba(4 * kBlocksWidth * kBlocksHeight, 0);
  for (int y = 0; y < kBlocksHeight; ++y) {
    for (int x = 0; x < kBlocksWidth; ++x)
      rgba[4 * (y * kBlocksWidth + x) + 1] = static_cast<std::uint8_t>(x / 30);
  }
  EXPECT_TRUE(covered_blocks(rgba).empty());
}

TEST(FxaaBlocks, OneVerticalEdgeGivesOneBlockARow) {
  std::vector<std::uint8_t> rgba(4 * kBlocksWidth * kBlocksHeight, 40);
  for (int y = 0; y < kBlocksHeight; ++y) {
    for (int x = 50; x < kBlocksWidth; ++x) rgba[4 * (y * kBlocksWidth + x) + 1] = 200;
  }
  std::vector<BlockRun> runs;
  find_edge_blocks(rgba.data(), kBlocksWidth, kBlocksHeight, runs);
  // Pixels 49 and 50 see the step; they lie in block columns 12 (48..51): one block a row.
  const int rows = (kBlocksHeight + kEdgeBlock - 1) / kEdgeBlock;
  ASSERT_EQ(static_cast<int>(runs.size()), rows);
  for (int r = 0; r < rows; ++r) {
    EXPECT_EQ(runs[static_cast<std::size_t>(r)].row, r);
    EXPECT_EQ(runs[static_cast<std::size_t>(r)].first, 12);
    EXPECT_EQ(runs[static_cast<std::size_t>(r)].count, 1);
  }
}

/// The blocks' test at one pixel, in integers, as the header states it: the green range over
/// the pixel, its four sides and two diagonals (clamped), at least 8 and 8 * range >= hi - 1.
bool integer_test_passes(const std::vector<std::uint8_t>& rgba, int width, int height, int x,
                         int y) {
  const auto at = [&](int px, int py) {
    px = std::clamp(px, 0, width - 1);
    py = std::clamp(py, 0, height - 1);
    return static_cast<int>(rgba[4 * static_cast<std::size_t>(py * width + px) + 1]);
  };
  const int v[7] = {at(x, y),     at(x, y + 1),     at(x + 1, y),    at(x, y - 1),
                    at(x - 1, y), at(x + 1, y + 1), at(x - 1, y - 1)};
  const int lo = *std::min_element(v, v + 7);
  const int hi = *std::max_element(v, v + 7);
  return hi - lo >= 8 && 8 * (hi - lo) >= hi - 1;
}

TEST(FxaaBlocks, RunsAreTheBlocksWhereSomePixelPassesAsLongAsTheyCanBe) {
  // Random sizes (most not multiples of the block side, down to one pixel) and contents
  // (noise, faint noise, sparse dark dots, a range of 7 to 8 at the threshold), against every
  // pixel tested one by one: the same blocks, in maximal runs, row by row, left to right.
  std::mt19937 random(11);
  for (int trial = 0; trial < 400; ++trial) {
    const int width = 1 + static_cast<int>(random() % 70);
    const int height = 1 + static_cast<int>(random() % 50);
    const int kind = static_cast<int>(random() % 4);
    std::vector<std::uint8_t> rgba(4 * static_cast<std::size_t>(width * height));
    for (std::uint8_t& byte : rgba) {
      const auto r = static_cast<std::uint32_t>(random());
      byte = static_cast<std::uint8_t>(kind == 0   ? r % 256
                                       : kind == 1 ? 100 + r % 12
                                       : kind == 2 ? (r % 9 != 0 ? 200 : 30)
                                                   : 40 + r % 9);
    }
    std::set<std::pair<int, int>> expected;
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        if (integer_test_passes(rgba, width, height, x, y))
          expected.insert({y / kEdgeBlock, x / kEdgeBlock});
      }
    }
    std::vector<BlockRun> runs;
    find_edge_blocks(rgba.data(), width, height, runs);
    std::set<std::pair<int, int>> found;
    for (std::size_t i = 0; i < runs.size(); ++i) {
      const BlockRun& run = runs[i];
      ASSERT_GT(run.count, 0);
      for (int b = 0; b < run.count; ++b) found.insert({run.row, run.first + b});
      if (i == 0) continue;
      const BlockRun& before = runs[i - 1];
      // In order, and never touching the run before it in the same row.
      EXPECT_TRUE(before.row < run.row ||
                  (before.row == run.row && before.first + before.count < run.first))
          << "trial " << trial << " run " << i;
    }
    EXPECT_EQ(found, expected) << "trial " << trial << ": " << width << "x" << height;
  }
}

/// Per pixel of a 64x48 grid: how many of `boxes` cover it.
std::vector<int> cover_counts(const std::vector<PixelBox>& boxes) {
  std::vector<int> counts(64 * 48, 0);
  for (const PixelBox& box : boxes) {
    for (int y = std::max(0, box.y0); y < std::min(48, box.y1); ++y) {
      for (int x = std::max(0, box.x0); x < std::min(64, box.x1); ++x) ++counts[y * 64 + x];
    }
  }
  return counts;
}

TEST(DisjointCover, CoversTheUnionOncePerPixel) {
  // Random boxes (some empty, some repeated, nested or touching) on a small grid against a
  // pixel count: the cover holds every pixel of the union exactly once and nothing else.
  std::mt19937 random(31);
  std::uniform_int_distribution<int> coordinate(0, 64), count(0, 5);
  for (int trial = 0; trial < 500; ++trial) {
    std::vector<PixelBox> boxes(static_cast<std::size_t>(count(random)));
    for (PixelBox& box : boxes) {
      const int a = coordinate(random), b = coordinate(random);
      const int c = coordinate(random) * 3 / 4, d = coordinate(random) * 3 / 4;
      box = {std::min(a, b), std::min(c, d), std::max(a, b), std::max(c, d)};
    }
    if (trial % 7 == 0 && !boxes.empty()) boxes.push_back(boxes.front());
    const std::vector<PixelBox> cover = disjoint_cover(boxes);
    const std::vector<int> wanted = cover_counts(boxes), got = cover_counts(cover);
    for (std::size_t pixel = 0; pixel < wanted.size(); ++pixel) {
      ASSERT_EQ(got[pixel], wanted[pixel] > 0 ? 1 : 0) << "trial " << trial << " pixel " << pixel;
    }
    for (const PixelBox& box : cover) {
      EXPECT_LT(box.x0, box.x1);
      EXPECT_LT(box.y0, box.y1);
    }
  }
}

TEST(DisjointCover, OverlappingFramesBoxesBecomeFewRectangles) {
  // A box, the same box again and one inside it: the box alone.
  const PixelBox box{8, 16, 200, 120};
  const std::vector<PixelBox> same = disjoint_cover({box, box, {20, 30, 40, 50}});
  ASSERT_EQ(same.size(), 1u);
  EXPECT_EQ(same[0].x0, 8);
  EXPECT_EQ(same[0].y1, 120);
  // The last frame's box and this one's, shifted by 8 pixels each way: three rectangles (the
  // band below, the shared band, the band above) holding the union, 192 x 104 twice less the
  // 184 x 96 both cover, each pixel once.
  const std::vector<PixelBox> shifted = disjoint_cover({box, {16, 24, 208, 128}});
  EXPECT_EQ(shifted.size(), 3u);
  long area = 0;
  for (const PixelBox& b : shifted) area += long{b.x1 - b.x0} * (b.y1 - b.y0);
  EXPECT_EQ(area, 192L * 104 + 192L * 104 - 184L * 96);
  EXPECT_TRUE(disjoint_cover({}).empty());
  EXPECT_TRUE(disjoint_cover({{5, 5, 5, 9}, {3, 7, 9, 7}}).empty());
}

}  // namespace
}  // namespace tumble::render::detail
