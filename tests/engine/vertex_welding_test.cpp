// weld_positions on inputs large enough for its two-thread path (from 2^20 vertices on), where
// the numbering is split between threads and duplicates cross the split.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <map>
#include <random>
#include <vector>

#include "engine/vertex_welding.hpp"

namespace tumble::engine {
namespace {

TEST(WeldPositions, TwoThreadWeldMatchesFirstOccurrenceNumbering) {
  // 1.5 M float positions from 40,000 distinct points, every 7th copy with -0. Blocks in random
  // order (most repeats far apart, many crossing the two threads' halves) alternate with blocks
  // in strip order (repeats a few vertices apart, as in a mesh file, caught by the weld's cache).
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> coordinate(-40, 40);
  std::vector<std::array<float, 3>> distinct(40'000);
  for (auto& p : distinct) {
    for (float& c : p) c = static_cast<float>(coordinate(rng)) * 0.25f;
  }
  std::uniform_int_distribution<std::size_t> pick(0, distinct.size() - 1);
  std::vector<std::array<float, 3>> positions(1'500'000);
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const bool strip = (i / 50'000) % 2 == 1;
    positions[i] = strip ? distinct[(i / 3 + i % 3) % distinct.size()] : distinct[pick(rng)];
    if (i % 7 == 0) {
      for (float& c : positions[i]) c = c == 0.0f ? -0.0f : c;
    }
  }

  // The oracle: an ordered map numbering positions by first occurrence (-0 folded onto +0).
  std::map<std::array<float, 3>, std::uint32_t> number_of;
  std::vector<std::uint32_t> expected_index(positions.size());
  std::vector<std::uint32_t> expected_kept;
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const std::array<float, 3> key{positions[i][0] + 0.0f, positions[i][1] + 0.0f,
                                   positions[i][2] + 0.0f};
    const auto [it, inserted] =
        number_of.try_emplace(key, static_cast<std::uint32_t>(expected_kept.size()));
    if (inserted) expected_kept.push_back(static_cast<std::uint32_t>(i));
    expected_index[i] = it->second;
  }

  const WeldMap map =
      weld_positions<float>(positions.size(), [&](std::size_t i) { return positions[i]; });

  ASSERT_EQ(map.kept, expected_kept);
  std::size_t mismatches = 0;
  for (std::size_t i = 0; i < positions.size(); ++i) {
    if (map.new_index[i] != expected_index[i]) ++mismatches;
  }
  EXPECT_EQ(mismatches, 0u);
}

}  // namespace
}  // namespace tumble::engine
