// weld_positions on inputs large enough for its two-thread path (from 2^20 vertices on), where
// the numbering is split between threads and duplicates cross the split.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <random>
#include <span>
#include <vector>

#include "engine/geometry/vertex_welding.hpp"  // engine/src: private to the engine

namespace tumble::engine {
namespace {

/// Welded numbering by first occurrence, computed with an ordered map (-0 folded onto +0).
struct Oracle {
  std::vector<std::uint32_t> index;
  std::vector<std::uint32_t> kept;
};

Oracle first_occurrence_numbering(const std::vector<std::array<float, 3>>& positions) {
  std::map<std::array<float, 3>, std::uint32_t> number_of;
  Oracle oracle;
  oracle.index.resize(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const std::array<float, 3> key{positions[i][0] + 0.0f, positions[i][1] + 0.0f,
                                   positions[i][2] + 0.0f};
    const auto [it, inserted] =
        number_of.try_emplace(key, static_cast<std::uint32_t>(oracle.kept.size()));
    if (inserted) oracle.kept.push_back(static_cast<std::uint32_t>(i));
    oracle.index[i] = it->second;
  }
  return oracle;
}

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

  const Oracle expected = first_occurrence_numbering(positions);
  const WeldMap map =
      weld_positions<float>(positions.size(), [&](std::size_t i) { return positions[i]; });

  ASSERT_EQ(map.kept, expected.kept);
  std::size_t mismatches = 0;
  for (std::size_t i = 0; i < positions.size(); ++i) {
    if (map.new_index[i] != expected.index[i]) ++mismatches;
  }
  EXPECT_EQ(mismatches, 0u);
}

TEST(WeldPositions, ScratchMemoryGivesTheSameWeld) {
  // Two inputs of 1.2 M float positions (two threads): one in strip order over 2,000 points,
  // whose few candidates and partitioned records all fit in the scratch memory (duplicates in
  // the second half all go back to the first), and one mostly in random order, whose
  // candidates overflow each thread's half of it and whose records do not fit.
  // Scratch memory of 12 bytes per vertex (assimp's normals), of 4.5 (little beyond the index
  // map), of 3 (too small: not used) and misaligned (not used) must all give the oracle's weld.
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> coordinate(-30, 30);
  std::vector<std::array<float, 3>> distinct(60'000);
  for (auto& p : distinct) {
    for (float& c : p) c = static_cast<float>(coordinate(rng)) * 0.5f;
  }
  std::uniform_int_distribution<std::size_t> pick(0, distinct.size() - 1);
  const std::size_t count = 1'200'000;
  std::vector<std::array<float, 3>> strips(count), scattered(count);
  for (std::size_t i = 0; i < count; ++i) {
    strips[i] = distinct[(i / 3 + i % 3) % 2'000];  // repeats within the weld's cache
    scattered[i] = (i / 40'000) % 4 == 3 ? strips[i] : distinct[pick(rng)];
    if (i % 5 == 0) {
      for (float& c : scattered[i]) c = c == 0.0f ? -0.0f : c;
    }
  }

  for (const auto* positions : {&strips, &scattered}) {
    const Oracle oracle = first_occurrence_numbering(*positions);
    for (const double bytes_per_vertex : {12.0, 4.5, 3.0, -12.0}) {
      SCOPED_TRACE(::testing::Message() << (positions == &strips ? "strips" : "scattered")
                                        << ", scratch bytes per vertex " << bytes_per_vertex);
      // 16-byte aligned memory, filled with garbage; a negative size asks for a misaligned span.
      const auto bytes = static_cast<std::size_t>(std::abs(bytes_per_vertex) * count);
      std::vector<std::array<float, 4>> memory(bytes / 16 + 2);
      std::span<std::byte> scratch(reinterpret_cast<std::byte*>(memory.data()), bytes);
      std::fill(scratch.begin(), scratch.end(), std::byte{0xa5});
      if (bytes_per_vertex < 0) scratch = scratch.subspan(1);

      const WeldMap map = weld_positions<float>(
          count, [&](std::size_t i) { return (*positions)[i]; }, scratch);
      ASSERT_EQ(map.kept, oracle.kept);
      std::size_t mismatches = 0;
      for (std::size_t i = 0; i < count; ++i) {
        if (map.new_index[i] != oracle.index[i]) ++mismatches;
      }
      EXPECT_EQ(mismatches, 0u);
      const bool in_scratch = bytes_per_vertex >= 4.0;
      const auto* scratch_start = reinterpret_cast<const std::uint32_t*>(scratch.data());
      EXPECT_EQ(map.new_index == scratch_start, in_scratch);
    }
  }
}

}  // namespace
}  // namespace tumble::engine
