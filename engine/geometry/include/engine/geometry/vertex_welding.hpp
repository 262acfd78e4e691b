#pragma once
/// @file Grouping vertices at bit-identical positions, for any coordinate type.
///
/// Used on doubles by the analysis pipeline and on assimp's floats by the importer (so that a
/// 1M-triangle STL soup is welded before it is ever widened to doubles). Linear time,
/// deterministic (the result does not depend on the thread split or on the cache below), two
/// threads from a million vertices on, and cache-friendly:
/// 1. in input order, a small direct-mapped cache of recent positions (slot from a cheap
///    hash) links most duplicates to an equal earlier vertex (mesh files list neighbouring
///    triangles together, so most of an STL soup's repeats are caught here: 0.56 M of 3 M
///    vertices left on the benchmark's torus);
/// 2. the rest, (index, position) records, are partitioned by the hash's top bits into at most
///    256 buckets (stably, so each bucket stays in index order);
/// 3. each bucket is grouped exactly with a small open-addressing table that stays in cache;
/// 4. links are followed and the survivors numbered, in input order, on both threads.
/// No node-based maps, no reads of the position array in random order.

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <numeric>
#include <span>
#include <stdexcept>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace tumble::engine {

/// The outcome of welding `count` vertices.
struct WeldMap {
  /// Welded index of each input vertex (`count` entries; an array, not a vector, so that its
  /// 4 bytes per vertex are written once rather than zeroed first). It points either into
  /// `storage` or into the scratch memory given to weld_positions.
  std::uint32_t* new_index = nullptr;
  std::vector<std::uint32_t> kept;           ///< input index of each welded vertex, ascending
  std::unique_ptr<std::uint32_t[]> storage;  ///< new_index's memory when no scratch held it
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

/// Element-wise comparison: std::array's operator== becomes a memcmp call, not inlined, which
/// cost more than the rest of the cache pass.
template <typename B>
bool same_bits(const std::array<B, 3>& a, const std::array<B, 3>& b) {
  return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
}

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

/// A cheap hash for the recent-position cache of the first pass: three independent multiplies
/// instead of position_hash's chain of rounds, so the slot is known a few cycles after the
/// position is read (the first pass ran ~25% faster). Its top bits pick the slot. Its quality
/// only decides how many duplicates the cache catches, never the result.
template <typename B>
std::uint32_t cache_hash(const std::array<B, 3>& bits) {
  if constexpr (sizeof(B) == 4) {
    return (bits[0] * 0x9e3779b1u) ^ (bits[1] * 0x85ebca77u) ^ (bits[2] * 0xc2b2ae3du);
  } else {
    const std::uint64_t h = (bits[0] * 0x9e3779b97f4a7c15ull) ^ (bits[1] * 0xc2b2ae3d27d4eb4full) ^
                            (bits[2] * 0x165667b19e3779f9ull);
    return static_cast<std::uint32_t>(h >> 32);
  }
}

/// Starts the lifetime of `count` objects of trivial type T at `memory` (no initialisation).
template <typename T>
T* reuse_as(std::byte* memory, std::size_t count) {
  static_assert(std::is_trivially_default_constructible_v<T> &&
                std::is_trivially_destructible_v<T>);
  T* const objects = reinterpret_cast<T*>(memory);
  std::uninitialized_default_construct_n(objects, count);
  return objects;
}

}  // namespace welding_detail

/// Asks the kernel to back the 2 MiB-aligned interior of a large buffer that is not yet touched
/// with transparent huge pages. The welding and topology temporaries of a million-triangle mesh
/// are fresh memory of tens of MB; with 4 KiB pages, faulting them in cost more than the
/// passes that fill them. Linux only (elsewhere a no-op); only a hint, so failure is ignored.
inline void advise_huge_pages(const void* data, std::size_t bytes) {
#if defined(MADV_HUGEPAGE)
  constexpr std::uintptr_t kHuge = std::uintptr_t{1} << 21;
  const auto address = reinterpret_cast<std::uintptr_t>(data);
  const std::uintptr_t begin = (address + kHuge - 1) & ~(kHuge - 1);
  const std::uintptr_t end = (address + bytes) & ~(kHuge - 1);
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#else
  (void)data;
  (void)bytes;
#endif
}

namespace welding_detail {

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

/// The state of one weld, pass by pass (weld_positions below describes the passes). Large
/// inputs are split between two threads: each takes a slice of the indices in the passes that
/// run in input order, and every other bucket in the grouping pass.
template <typename Scalar, typename PositionOf>
class Welder {
 public:
  Welder(std::size_t count, PositionOf& position)
      : count_(count),
        position_(position),
        threads_(count >= (std::size_t{1} << 20) ? 2 : 1),
        // At most 256 partitions: more scatter streams than that defeat write combining; a
        // bucket of ~10k records still keeps its table in L2.
        partition_bits_(std::clamp(static_cast<int>(std::bit_width(count / 4096)), 1, 8)),
        partitions_(std::size_t{1} << partition_bits_),
        shift_(32 - partition_bits_) {}

  void place_index_map(std::span<std::byte> scratch);
  void link_recent_duplicates();
  void partition_candidates();
  void group_buckets();
  void resolve_links();
  WeldMap number_survivors();

 private:
  using Rec = Record<Scalar>;

  /// Runs work(thread) on each thread (the calling thread is thread 0).
  template <typename Work>
  void parallel(const Work& work) const {
    if (threads_ == 1) return work(0);
    std::thread helper([&] { work(1); });
    work(0);
    helper.join();
  }
  /// The input indices [first, last) of a thread.
  std::pair<std::size_t, std::size_t> slice(int thread) const {
    const auto t = static_cast<std::size_t>(thread);
    const auto n = static_cast<std::size_t>(threads_);
    return {count_ * t / n, count_ * (t + 1) / n};
  }
  std::array<Bits<Scalar>, 3> bits_of(std::size_t i) const {
    const std::array<Scalar, 3> p = position_(i);
    return {coordinate_bits(p[0]), coordinate_bits(p[1]), coordinate_bits(p[2])};
  }
  void place_candidates();
  void cache_pass(int thread);

  const std::size_t count_;
  PositionOf& position_;
  const int threads_;
  const int partition_bits_;
  const std::size_t partitions_;
  const int shift_;
  WeldMap map_;
  std::uint32_t* index_ = nullptr;
  std::byte* free_scratch_ = nullptr;
  std::size_t free_records_ = 0;  ///< records of Rec that fit after the index map
  Rec* in_scratch_ = nullptr;
  std::unique_ptr<Rec[]> candidates_storage_;
  std::size_t half_ = 0;
  std::vector<std::size_t> candidates_end_ = std::vector<std::size_t>(threads_);
  std::vector<std::vector<Rec>> overflow_ = std::vector<std::vector<Rec>>(threads_);
  std::vector<std::vector<std::size_t>> counts_ =
      std::vector<std::vector<std::size_t>>(threads_, std::vector<std::size_t>(partitions_, 0));
  std::vector<std::size_t> start_ = std::vector<std::size_t>(partitions_ + 1, 0);
  std::unique_ptr<Rec[]> records_storage_;
  Rec* records_ = nullptr;
  std::vector<std::size_t> survivors_ = std::vector<std::size_t>(threads_, 0);
};

/// The output array holds, in turn: a link to an equal earlier vertex, the representative, and
/// the welded index. It is written before it is read, so it is not zeroed first. Scratch
/// memory, when large enough, holds it first and then the candidates: the first thread's from
/// the front of the rest, the second thread's from its back, so that the middle stays free for
/// the partitioned records when the candidates take at most half of it.
template <typename Scalar, typename PositionOf>
void Welder<Scalar, PositionOf>::place_index_map(std::span<std::byte> scratch) {
  if (!scratch.empty() && scratch.size() >= count_ * sizeof(std::uint32_t) &&
      reinterpret_cast<std::uintptr_t>(scratch.data()) % alignof(Rec) == 0) {
    map_.new_index = reuse_as<std::uint32_t>(scratch.data(), count_);
    constexpr std::size_t kAlign = alignof(Rec);
    const std::size_t index_bytes = (count_ * sizeof(std::uint32_t) + kAlign - 1) & ~(kAlign - 1);
    if (scratch.size() > index_bytes) {
      free_scratch_ = scratch.data() + index_bytes;
      free_records_ = (scratch.size() - index_bytes) / sizeof(Rec);
    }
  } else {
    map_.storage = std::make_unique_for_overwrite<std::uint32_t[]>(count_);
    advise_huge_pages(map_.storage.get(), count_ * sizeof(std::uint32_t));
    map_.new_index = map_.storage.get();
  }
  index_ = map_.new_index;
}

/// Without scratch memory, each thread writes its candidates at the start of its own slice of
/// one array as large as the input; only the part written is ever touched. With scratch
/// memory, each thread has half of it (the second thread filling its half from the back);
/// candidates beyond that go to a vector.
template <typename Scalar, typename PositionOf>
void Welder<Scalar, PositionOf>::place_candidates() {
  half_ = free_records_ / 2;
  if (half_ > 0) {
    in_scratch_ = reuse_as<Rec>(free_scratch_, free_records_);
  } else {
    candidates_storage_ = std::make_unique_for_overwrite<Rec[]>(count_);
    advise_huge_pages(candidates_storage_.get(), count_ * sizeof(Rec));
  }
}

/// Pass 1, in input order: a small direct-mapped cache of recently seen positions catches most
/// duplicates where they are cheap to catch. Meshes list neighbouring triangles close together,
/// so in an STL soup (each position about six times) most repeats are recent. A vertex found in
/// the cache is linked to the earlier vertex there; the others (every first occurrence among
/// them) become candidates for the exact grouping below. The cache only decides how much work
/// is left: the result is the same whatever it catches.
template <typename Scalar, typename PositionOf>
void Welder<Scalar, PositionOf>::link_recent_duplicates() {
  place_candidates();
  parallel([&](int thread) { cache_pass(thread); });
}

template <typename Scalar, typename PositionOf>
void Welder<Scalar, PositionOf>::cache_pass(int thread) {
  const auto [first, last] = slice(thread);
  // Candidates go to candidates[found], found counting up; in the second thread's half of the
  // scratch, they go to candidates[-found], from its back.
  Rec* const candidates = in_scratch_ == nullptr ? candidates_storage_.get()
                          : thread == 0          ? in_scratch_
                                                 : in_scratch_ + free_records_ - 1;
  const std::ptrdiff_t step = in_scratch_ != nullptr && thread == 1 ? -1 : 1;
  const std::size_t capacity = in_scratch_ == nullptr ? last : half_;
  // 8192 slots (128 KiB of float records) stay in L2; small meshes get a smaller cache.
  const int cache_bits = std::clamp(static_cast<int>(std::bit_width(count_)), 1, 13);
  std::vector<Rec> cache(std::size_t{1} << cache_bits, Rec{kNone, {}});
  std::size_t found = in_scratch_ == nullptr ? first : 0;
  std::vector<std::size_t>& counted = counts_[static_cast<std::size_t>(thread)];
  std::vector<Rec>& overflow = overflow_[static_cast<std::size_t>(thread)];
  std::uint32_t* const index = index_;
  const int shift = shift_;
  for (std::size_t i = first; i < last; ++i) {
    const auto bits = bits_of(i);
    Rec& cached = cache[cache_hash(bits) >> (32 - cache_bits)];
    if (cached.index != kNone && same_bits(cached.bits, bits)) {
      index[i] = cached.index;
      continue;
    }
    const std::uint32_t hash = position_hash<Scalar>(bits);
    cached = {static_cast<std::uint32_t>(i), bits};
    index[i] = static_cast<std::uint32_t>(i);
    if (found < capacity) {
      candidates[static_cast<std::ptrdiff_t>(found++) * step] = cached;
    } else {
      overflow.push_back(cached);
    }
    ++counted[hash >> shift];
  }
  candidates_end_[static_cast<std::size_t>(thread)] = found;
}

/// Pass 2: partition the candidates by the hash's top bits. Each thread scatters its own
/// candidates into its slice of every bucket (the first slice first), so each bucket stays in
/// index order.
template <typename Scalar, typename PositionOf>
void Welder<Scalar, PositionOf>::partition_candidates() {
  const auto threads = static_cast<std::size_t>(threads_);
  std::vector<std::vector<std::size_t>> fill(threads, std::vector<std::size_t>(partitions_));
  for (std::size_t part = 0, offset = 0; part < partitions_; ++part) {
    start_[part] = offset;
    for (std::size_t thread = 0; thread < threads; ++thread) {
      fill[thread][part] = offset;
      offset += counts_[thread][part];
    }
    start_[part + 1] = offset;
  }
  const std::size_t candidate_count = start_[partitions_];
  // The records go between the two threads' candidates in the scratch memory when they fit.
  const std::size_t in_scratch_count = candidates_end_[0] + (threads > 1 ? candidates_end_[1] : 0);
  if (in_scratch_ != nullptr && free_records_ - in_scratch_count >= candidate_count) {
    records_ = in_scratch_ + candidates_end_[0];
  } else {
    records_storage_ = std::make_unique_for_overwrite<Rec[]>(candidate_count);
    advise_huge_pages(records_storage_.get(), candidate_count * sizeof(Rec));
    records_ = records_storage_.get();
  }
  parallel([&](int thread) {
    const auto t = static_cast<std::size_t>(thread);
    std::vector<std::size_t>& next = fill[t];
    Rec* const records = records_;
    const int shift = shift_;
    const auto scatter = [&](const Rec& record) {
      records[next[position_hash<Scalar>(record.bits) >> shift]++] = record;
    };
    if (in_scratch_ == nullptr) {
      for (std::size_t c = slice(thread).first; c < candidates_end_[t]; ++c) {
        scatter(candidates_storage_[c]);
      }
    } else {
      for (std::size_t c = 0; c < candidates_end_[t]; ++c) {
        scatter(thread == 0 ? in_scratch_[c] : in_scratch_[free_records_ - 1 - c]);
      }
      for (const Rec& record : overflow_[t]) scatter(record);
    }
  });
}

/// Pass 3: group each bucket with a small open-addressing table; the first (lowest) candidate
/// at a position, which is the position's first occurrence, represents it.
template <typename Scalar, typename PositionOf>
void Welder<Scalar, PositionOf>::group_buckets() {
  parallel([&](int thread) {
    std::vector<std::uint32_t> table;
    const Rec* const records = records_;
    std::uint32_t* const index = index_;
    for (auto part = static_cast<std::size_t>(thread); part < partitions_;
         part += static_cast<std::size_t>(threads_)) {
      const std::size_t begin = start_[part];
      const std::size_t end = start_[part + 1];
      const std::size_t slots = std::bit_ceil(2 * (end - begin) + 1);
      table.assign(slots, kNone);
      for (std::size_t r = begin; r < end; ++r) {
        const Rec& record = records[r];
        const std::uint32_t hash = position_hash<Scalar>(record.bits);
        for (std::size_t slot = hash & (slots - 1);; slot = (slot + 1) & (slots - 1)) {
          if (table[slot] == kNone) {
            table[slot] = static_cast<std::uint32_t>(r);
            break;
          }
          const Rec& held = records[table[slot]];
          if (same_bits(held.bits, record.bits)) {
            index[record.index] = held.index;
            break;
          }
        }
      }
    }
  });
}

/// Pass 4, in input order: follow each cache link to its candidate's representative (the
/// linked candidate is earlier in the same slice, so already resolved; a link into an earlier
/// slice is a representative itself, taken as it is rather than read while the other thread
/// rewrites that slice), and count the survivors of each slice.
template <typename Scalar, typename PositionOf>
void Welder<Scalar, PositionOf>::resolve_links() {
  parallel([&](int thread) {
    const auto [first, last] = slice(thread);
    std::uint32_t* const index = index_;
    std::size_t kept = 0;
    for (std::size_t i = first; i < last; ++i) {
      const std::uint32_t link = index[i];
      const std::uint32_t representative = link < first ? link : index[link];
      index[i] = representative;
      kept += representative == i ? 1 : 0;
    }
    survivors_[static_cast<std::size_t>(thread)] = kept;
  });
}

/// Pass 5: number the survivors in their original order, in place; each thread knows how many
/// survivors precede its slice. A representative precedes its duplicates, so inside the slice
/// it is already numbered; a duplicate whose representative lies in the first slice is
/// resolved after the join (only the second thread defers).
template <typename Scalar, typename PositionOf>
WeldMap Welder<Scalar, PositionOf>::number_survivors() {
  map_.kept.resize(survivors_[0] + (threads_ > 1 ? survivors_[1] : 0));
  std::vector<std::uint32_t> deferred;
  parallel([&](int thread) {
    const auto [first, last] = slice(thread);
    std::uint32_t* const index = index_;
    auto next = static_cast<std::uint32_t>(thread == 0 ? 0 : survivors_[0]);
    for (std::size_t i = first; i < last; ++i) {
      const std::uint32_t representative = index[i];
      if (representative == i) {
        map_.kept[next] = representative;
        index[i] = next++;
      } else if (representative >= first) {
        index[i] = index[representative];
      } else {
        deferred.push_back(static_cast<std::uint32_t>(i));
      }
    }
  });
  for (const std::uint32_t i : deferred) index_[i] = index_[index_[i]];
  return std::move(map_);
}

}  // namespace welding_detail

/// Welds `count` vertices whose coordinates `position(i)` returns as std::array<Scalar, 3>.
/// Vertices with bit-identical coordinates (-0 == +0) share one index; survivors keep their
/// order of first appearance.
///
/// `scratch` (optional, 16-byte aligned, contents destroyed) is memory the caller no longer
/// needs, such as the normals assimp read along with an STL's positions: the index map and the
/// temporaries are placed in it as far as it goes, so that fewer fresh pages are faulted in
/// (a million-triangle soup needs ~30 MB of them otherwise). The index map then lives in the
/// scratch memory, and is valid as long as it is. The result does not depend on the scratch.
template <typename Scalar, typename PositionOf>
WeldMap weld_positions(std::size_t count, PositionOf position, std::span<std::byte> scratch = {}) {
  if (count >= std::numeric_limits<std::uint32_t>::max()) {
    throw std::length_error("weld_positions: more than 2^32 - 1 vertices");
  }
  welding_detail::Welder<Scalar, PositionOf> welder(count, position);
  welder.place_index_map(scratch);   // the index map, in the scratch memory when it fits
  welder.link_recent_duplicates();   // pass 1: a cache of recent positions links most repeats
  welder.partition_candidates();     // pass 2: the rest into buckets by hash
  welder.group_buckets();            // pass 3: exact grouping per bucket
  welder.resolve_links();            // pass 4: every vertex to its representative
  return welder.number_survivors();  // pass 5: survivors numbered in input order
}

}  // namespace tumble::engine
