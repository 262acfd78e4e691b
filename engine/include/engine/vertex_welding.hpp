#pragma once
/// @file Grouping vertices at bit-identical positions, for any coordinate type.
///
/// Used on doubles by the analysis pipeline and on assimp's floats by the importer (so that a
/// 1M-triangle STL soup is welded before it is ever widened to doubles). Linear time and
/// cache-friendly: each position is hashed, (hash, index, position) records are partitioned
/// by the hash's top bits into buckets of about a thousand (stably, so each bucket stays in
/// index order), and each bucket is grouped exactly with a small open-addressing table that
/// stays in cache. No node-based maps, no reads of the position array in random order.

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <vector>

namespace tumble::engine {

/// The outcome of welding `count` vertices.
struct WeldMap {
  std::vector<std::uint32_t> new_index;  ///< welded index of each input vertex
  std::vector<std::uint32_t> kept;       ///< input index of each welded vertex, ascending
};

namespace welding_detail {

template <typename Scalar>
using Bits = std::conditional_t<sizeof(Scalar) == 8, std::uint64_t, std::uint32_t>;

/// Bits of a coordinate with -0 folded onto +0, so equal values compare and hash equal.
template <typename Scalar>
Bits<Scalar> coordinate_bits(Scalar value) {
  return std::bit_cast<Bits<Scalar>>(value == Scalar(0) ? Scalar(0) : value);
}

template <typename Scalar>
struct Record {
  std::uint32_t hash;
  std::uint32_t index;
  std::array<Bits<Scalar>, 3> bits;
};

}  // namespace welding_detail

/// Welds `count` vertices whose coordinates `position(i)` returns as std::array<Scalar, 3>.
/// Vertices with bit-identical coordinates (-0 == +0) share one index; survivors keep their
/// order of first appearance.
template <typename Scalar, typename PositionOf>
WeldMap weld_positions(std::size_t count, PositionOf position) {
  using namespace welding_detail;
  if (count >= std::numeric_limits<std::uint32_t>::max()) {
    throw std::length_error("weld_positions: more than 2^32 - 1 vertices");
  }

  // Hash every position, then partition the records by the hash's top bits.
  const int partition_bits = std::clamp(static_cast<int>(std::bit_width(count / 1024)), 1, 16);
  const std::size_t partitions = std::size_t{1} << partition_bits;
  const int shift = 32 - partition_bits;
  const auto bits_of = [&](std::size_t i) {
    const std::array<Scalar, 3> p = position(i);
    return std::array<Bits<Scalar>, 3>{coordinate_bits(p[0]), coordinate_bits(p[1]),
                                       coordinate_bits(p[2])};
  };
  std::vector<std::uint32_t> hashes(count);
  std::vector<std::size_t> start(partitions + 1, 0);
  for (std::size_t i = 0; i < count; ++i) {
    std::uint64_t h = 0x9e3779b97f4a7c15ull;
    for (const auto bits : bits_of(i)) {
      h ^= bits;
      h *= 0xbf58476d1ce4e5b9ull;
      h ^= h >> 31;
    }
    hashes[i] = static_cast<std::uint32_t>((h * 0x94d049bb133111ebull) >> 32);
    ++start[(hashes[i] >> shift) + 1];
  }
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<Record<Scalar>> records(count);
  {
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (std::size_t i = 0; i < count; ++i) {
      records[fill[hashes[i] >> shift]++] = {hashes[i], static_cast<std::uint32_t>(i), bits_of(i)};
    }
  }

  // Group each bucket; the first (lowest) index at a position represents it.
  std::vector<std::uint32_t> representative(count);
  constexpr std::uint32_t kEmpty = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> table;
  for (std::size_t part = 0; part < partitions; ++part) {
    const std::size_t begin = start[part];
    const std::size_t end = start[part + 1];
    const std::size_t slots = std::bit_ceil(2 * (end - begin) + 1);
    table.assign(slots, kEmpty);
    for (std::size_t r = begin; r < end; ++r) {
      const Record<Scalar>& record = records[r];
      for (std::size_t slot = record.hash & (slots - 1);; slot = (slot + 1) & (slots - 1)) {
        if (table[slot] == kEmpty) {
          table[slot] = static_cast<std::uint32_t>(r);
          representative[record.index] = record.index;
          break;
        }
        const Record<Scalar>& held = records[table[slot]];
        if (held.hash == record.hash && held.bits == record.bits) {
          representative[record.index] = held.index;
          break;
        }
      }
    }
  }

  // Number the survivors in their original order.
  WeldMap map;
  map.new_index.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    if (representative[i] == i) {
      map.new_index[i] = static_cast<std::uint32_t>(map.kept.size());
      map.kept.push_back(static_cast<std::uint32_t>(i));
    } else {
      map.new_index[i] = map.new_index[representative[i]];
    }
  }
  return map;
}

}  // namespace tumble::engine
