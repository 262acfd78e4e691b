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

}  // namespace
}  // namespace tumble::render::detail
