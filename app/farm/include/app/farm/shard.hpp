#pragma once
/// @file One shard of a job: `--shard I/N` (I counted from 0) does the I-th of N parts, and the
/// parts of all N shards together are the whole job, each item exactly once.
///
/// Two ways to cut a list of items, both deterministic (the same on every machine):
/// - contiguous: shard I takes items [begin, end), the first `total % N` shards one more than
///   the others; for frames, so that a shard is one stretch of video.
/// - strided: shard I takes items I, I + N, I + 2N, ...; for cases and files, whose cost runs in
///   blocks (one scene's steps, one folder's meshes), so that each shard gets a share of each
///   block and the shards take about as long.

#include <cstddef>
#include <string>
#include <string_view>

namespace tumble::app {

struct Shard {
  int index = 0;  ///< I, from 0
  int count = 1;  ///< N, at least 1

  bool whole() const { return count == 1; }
  /// "I/N".
  std::string text() const;
  friend bool operator==(const Shard& a, const Shard& b) {
    return a.index == b.index && a.count == b.count;
  }
};

/// The largest N accepted: more shards than this is taken for a typo.
inline constexpr int kMaxShards = 100000;

/// Parses "I/N" (decimal integers, 0 <= I < N <= kMaxShards). Throws InputError naming
/// `option` ("--shard: expected I/N with 0 <= I < N, counted from 0, got '4/4'").
Shard parse_shard(std::string_view text, std::string_view option = "--shard");

enum class ShardSplit { kContiguous, kStrided };

/// "contiguous" or "strided".
std::string_view split_name(ShardSplit split);
/// The split named `name`; false if there is none.
bool parse_split_name(std::string_view name, ShardSplit& split);

/// The items [begin, end) of `shard` under a contiguous split of `total` items.
struct ItemRange {
  std::size_t begin = 0;
  std::size_t end = 0;
  std::size_t size() const { return end - begin; }
};
ItemRange contiguous_range(std::size_t total, Shard shard);

/// Whether item `item` belongs to `shard` under `split` of `total` items.
bool in_shard(std::size_t item, std::size_t total, Shard shard, ShardSplit split);

/// How many of `total` items belong to `shard` under `split`.
std::size_t shard_size(std::size_t total, Shard shard, ShardSplit split);

}  // namespace tumble::app
