#pragma once
/// @file Grouping vertices at bit-identical positions, for any coordinate type.
///
/// Used on doubles by the analysis pipeline and on assimp's floats by the importer (so that a
/// 1M-triangle STL soup is welded before it is ever widened to doubles). Linear time,
/// deterministic (the result does not depend on the thread split), two threads from a million
/// vertices on, and cache-friendly: each position is hashed, (hash, index, position) records are partitioned
/// by the hash's top bits into at most 256 buckets (stably, so each bucket stays in
/// index order), and each bucket is grouped exactly with a small open-addressing table that
/// stays in cache. No node-based maps, no reads of the position array in random order.

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <thread>
#include <utility>
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
  std::uint32_t index;
  std::array<Bits<Scalar>, 3> bits;
};

/// A 32-bit hash of a position's bits (multiply-xorshift rounds).
template <typename Scalar>
std::uint32_t position_hash(const std::array<Bits<Scalar>, 3>& bits) {
  std::uint64_t h = 0x9e3779b97f4a7c15ull;
  for (const auto b : bits) {
    h ^= b;
    h *= 0xbf58476d1ce4e5b9ull;
    h ^= h >> 31;
  }
  return static_cast<std::uint32_t>((h * 0x94d049bb133111ebull) >> 32);
}

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

  // Hash every position, then partition the records by the hash's top bits. Large inputs are
  // split between two threads: each hashes and scatters its half of the indices into its own
  // slice of every bucket (the first half's slice first, so buckets stay in index order),
  // then each groups half of the buckets.
  // At most 256 partitions: more scatter streams than that defeat write combining; a bucket of
  // ~10k records still keeps its table in L2.
  const int partition_bits = std::clamp(static_cast<int>(std::bit_width(count / 4096)), 1, 8);
  const std::size_t partitions = std::size_t{1} << partition_bits;
  const int shift = 32 - partition_bits;
  const auto bits_of = [&](std::size_t i) {
    const std::array<Scalar, 3> p = position(i);
    return std::array<Bits<Scalar>, 3>{coordinate_bits(p[0]), coordinate_bits(p[1]),
                                       coordinate_bits(p[2])};
  };
  const int threads = count >= (std::size_t{1} << 20) ? 2 : 1;
  const auto parallel = [&](const auto& work) {
    if (threads == 1) return work(0);
    std::thread helper([&] { work(1); });
    work(0);
    helper.join();
  };
  const auto slice = [&](int thread) {
    return std::pair{count * thread / threads, count * (thread + 1) / threads};
  };

  std::vector<std::vector<std::size_t>> counts(threads, std::vector<std::size_t>(partitions, 0));
  parallel([&](int thread) {
    const auto [first, last] = slice(thread);
    for (std::size_t i = first; i < last; ++i) {
      ++counts[thread][position_hash<Scalar>(bits_of(i)) >> shift];
    }
  });
  std::vector<std::size_t> start(partitions + 1, 0);
  std::vector<std::vector<std::size_t>> fill(threads, std::vector<std::size_t>(partitions));
  for (std::size_t part = 0, offset = 0; part < partitions; ++part) {
    start[part] = offset;
    for (int thread = 0; thread < threads; ++thread) {
      fill[thread][part] = offset;
      offset += counts[thread][part];
    }
    start[part + 1] = offset;
  }
  // The large temporaries are left uninitialised: every element is written before it is read
  // (value-initialising 60 MB of records cost more than the scatter itself). The hash is
  // recomputed wherever it is needed: cheaper than storing and reloading it.
  const auto records = std::make_unique_for_overwrite<Record<Scalar>[]>(count);
  parallel([&](int thread) {
    const auto [first, last] = slice(thread);
    std::vector<std::size_t>& next = fill[thread];
    for (std::size_t i = first; i < last; ++i) {
      const auto bits = bits_of(i);
      records[next[position_hash<Scalar>(bits) >> shift]++] = {static_cast<std::uint32_t>(i), bits};
    }
  });

  // Group each bucket; the first (lowest) index at a position represents it.
  const auto representative = std::make_unique_for_overwrite<std::uint32_t[]>(count);
  parallel([&](int thread) {
    constexpr std::uint32_t kEmpty = std::numeric_limits<std::uint32_t>::max();
    std::vector<std::uint32_t> table;
    for (std::size_t part = thread; part < partitions; part += threads) {
      const std::size_t begin = start[part];
      const std::size_t end = start[part + 1];
      const std::size_t slots = std::bit_ceil(2 * (end - begin) + 1);
      table.assign(slots, kEmpty);
      for (std::size_t r = begin; r < end; ++r) {
        const Record<Scalar>& record = records[r];
        const std::uint32_t hash = position_hash<Scalar>(record.bits);
        for (std::size_t slot = hash & (slots - 1);; slot = (slot + 1) & (slots - 1)) {
          if (table[slot] == kEmpty) {
            table[slot] = static_cast<std::uint32_t>(r);
            representative[record.index] = record.index;
            break;
          }
          const Record<Scalar>& held = records[table[slot]];
          if (held.bits[0] == record.bits[0] &&
              held.bits[1] == record.bits[1] && held.bits[2] == record.bits[2]) {
            representative[record.index] = held.index;
            break;
          }
        }
      }
    }
  });

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
