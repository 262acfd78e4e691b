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
#include <vector>

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

/// The items [begin, end) of `shard` when `total` items may be cut only where a block of
/// `block` items starts (video frames: at key frames, so that each segment starts where the
/// whole video has a key frame). Boundary i is the block start nearest i * total / N, moved
/// on where it would repeat the one before or leave too few blocks for the shards after it:
/// every shard takes at least one block (the last block may be shorter), and each boundary is
/// within half a block of the even split unless the blocks are too few for that. Empty for
/// every shard when there are fewer blocks, ceil(total / block), than shards.
ItemRange aligned_range(std::size_t total, std::size_t block, Shard shard);

/// Whether item `item` belongs to `shard` under `split` of `total` items.
bool in_shard(std::size_t item, std::size_t total, Shard shard, ShardSplit split);

/// How many of `total` items belong to `shard` under `split`.
std::size_t shard_size(std::size_t total, Shard shard, ShardSplit split);

/// The strided shard's items of `total`: shard.index, shard.index + N, ...
std::vector<std::size_t> shard_items(std::size_t total, Shard shard);

}  // namespace tumble::app
