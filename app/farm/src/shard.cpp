// Shards: "I/N" and the two deterministic splits of a list of items.
#include "app/farm/shard.hpp"

#include <algorithm>
#include <charconv>

#include "base/errors.hpp"

namespace tumble::app {

namespace {

/// A decimal integer filling all of `text`, or -1.
long parse_count(std::string_view text) {
  if (text.empty() || text.size() > 9) return -1;
  long value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size()) return -1;
  return value;
}

}  // namespace

std::string Shard::text() const {
  return std::to_string(index) + "/" + std::to_string(count);
}

Shard parse_shard(std::string_view text, std::string_view option) {
  const std::size_t slash = text.find('/');
  const long index = slash == std::string_view::npos ? -1 : parse_count(text.substr(0, slash));
  const long count = slash == std::string_view::npos ? -1 : parse_count(text.substr(slash + 1));
  if (index < 0 || count < 1 || index >= count || count > kMaxShards) {
    throw InputError(std::string(option) +
                     ": expected I/N with 0 <= I < N <= " + std::to_string(kMaxShards) +
                     " (shards counted from 0), got '" + std::string(text) + "'");
  }
  return Shard{static_cast<int>(index), static_cast<int>(count)};
}

std::string_view split_name(ShardSplit split) {
  return split == ShardSplit::kContiguous ? "contiguous" : "strided";
}

bool parse_split_name(std::string_view name, ShardSplit& split) {
  if (name == "contiguous") {
    split = ShardSplit::kContiguous;
  } else if (name == "strided") {
    split = ShardSplit::kStrided;
  } else {
    return false;
  }
  return true;
}

ItemRange contiguous_range(std::size_t total, Shard shard) {
  const auto count = static_cast<std::size_t>(shard.count);
  const auto index = static_cast<std::size_t>(shard.index);
  const std::size_t base = total / count;
  const std::size_t extra = total % count;
  // The first `extra` shards take base + 1 items each.
  const std::size_t begin = index * base + (index < extra ? index : extra);
  return ItemRange{begin, begin + base + (index < extra ? 1 : 0)};
}

ItemRange aligned_range(std::size_t total, std::size_t block, Shard shard) {
  if (block == 0) block = 1;
  const auto count = static_cast<std::size_t>(shard.count);
  const auto index = static_cast<std::size_t>(shard.index);
  const std::size_t blocks = total / block + (total % block != 0 ? 1 : 0);
  if (blocks < count) return ItemRange{};
  // Boundaries in blocks, each from the one before: b_0 = 0, b_N = blocks.
  std::size_t begin = 0;
  std::size_t end = blocks;
  std::size_t previous = 0;
  for (std::size_t i = 1; i <= index + 1 && i < count; ++i) {
    // round(i * total / (N * block)), in integers.
    const std::size_t nearest = (2 * i * total + count * block) / (2 * count * block);
    const std::size_t boundary = std::clamp(nearest, previous + 1, blocks - (count - i));
    if (i == index) begin = boundary;
    if (i == index + 1) end = boundary;
    previous = boundary;
  }
  return ItemRange{begin * block, std::min(end * block, total)};
}

bool in_shard(std::size_t item, std::size_t total, Shard shard, ShardSplit split) {
  if (item >= total) return false;
  if (split == ShardSplit::kStrided) {
    return item % static_cast<std::size_t>(shard.count) == static_cast<std::size_t>(shard.index);
  }
  const ItemRange range = contiguous_range(total, shard);
  return item >= range.begin && item < range.end;
}

std::size_t shard_size(std::size_t total, Shard shard, ShardSplit split) {
  if (split == ShardSplit::kContiguous) return contiguous_range(total, shard).size();
  const auto count = static_cast<std::size_t>(shard.count);
  const auto index = static_cast<std::size_t>(shard.index);
  return total / count + (index < total % count ? 1 : 0);
}

std::vector<std::size_t> shard_items(std::size_t total, Shard shard) {
  std::vector<std::size_t> items;
  for (std::size_t i = 0; i < total; ++i) {
    if (in_shard(i, total, shard, ShardSplit::kStrided)) items.push_back(i);
  }
  return items;
}

}  // namespace tumble::app
