// Shards: "I/N" parsed strictly, and both splits cover every item exactly once, balanced.
#include "app/farm/shard.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "base/errors.hpp"

namespace tumble::app {
namespace {

TEST(Shard, ParsesIndexAndCount) {
  EXPECT_EQ(parse_shard("0/1"), (Shard{0, 1}));
  EXPECT_EQ(parse_shard("3/4"), (Shard{3, 4}));
  EXPECT_EQ(parse_shard("99999/100000"), (Shard{99999, 100000}));
  EXPECT_EQ(parse_shard("2/7").text(), "2/7");
}

TEST(Shard, RefusesWhatIsNotIOfN) {
  for (const char* text : {"", "1", "/4", "1/", "4/4", "5/4", "-1/4", "1/0", "1/-2", "a/4", "1/4x",
                           " 1/4", "1.0/4", "0/100001", "1/2/3"}) {
    try {
      parse_shard(text);
      ADD_FAILURE() << "accepted '" << text << "'";
    } catch (const InputError& error) {
      EXPECT_THAT(error.what(), ::testing::StartsWith("--shard: expected I/N with 0 <= I < N"));
      EXPECT_THAT(error.what(), ::testing::HasSubstr("got '" + std::string(text) + "'"));
    }
  }
}

TEST(Shard, NamesTheOptionItWasGiven) {
  EXPECT_THROW(
      {
        try {
          parse_shard("9/3", "--tasks");
        } catch (const InputError& error) {
          EXPECT_THAT(error.what(), ::testing::StartsWith("--tasks: "));
          throw;
        }
      },
      InputError);
}

/// Every item of `total` in exactly one of `count` shards under `split`; sizes differ by <= 1
/// and agree with shard_size.
void expect_exact_cover(std::size_t total, int count, ShardSplit split) {
  std::vector<int> owners(total, 0);
  std::size_t smallest = total;
  std::size_t largest = 0;
  for (int index = 0; index < count; ++index) {
    const Shard shard{index, count};
    std::size_t size = 0;
    for (std::size_t item = 0; item < total; ++item) {
      if (in_shard(item, total, shard, split)) {
        ++owners[item];
        ++size;
      }
    }
    EXPECT_EQ(size, shard_size(total, shard, split)) << index << "/" << count;
    smallest = std::min(smallest, size);
    largest = std::max(largest, size);
  }
  for (std::size_t item = 0; item < total; ++item) {
    ASSERT_EQ(owners[item], 1) << "item " << item << " of " << total << " in " << count;
  }
  EXPECT_LE(largest - smallest, 1U) << total << " items in " << count;
}

TEST(Shard, BothSplitsCoverEveryItemOnceBalanced) {
  for (const std::size_t total : {0UL, 1UL, 2UL, 7UL, 480UL, 1001UL}) {
    for (const int count : {1, 2, 3, 4, 7, 16}) {
      expect_exact_cover(total, count, ShardSplit::kContiguous);
      expect_exact_cover(total, count, ShardSplit::kStrided);
    }
  }
}

TEST(Shard, ContiguousRangesFollowEachOther) {
  // 10 frames in 4 shards: 3, 3, 2, 2.
  const std::vector<std::pair<std::size_t, std::size_t>> expected{{0, 3}, {3, 6}, {6, 8}, {8, 10}};
  for (int index = 0; index < 4; ++index) {
    const ItemRange range = contiguous_range(10, Shard{index, 4});
    EXPECT_EQ(range.begin, expected[static_cast<std::size_t>(index)].first);
    EXPECT_EQ(range.end, expected[static_cast<std::size_t>(index)].second);
  }
  // More shards than items: the last ones are empty.
  EXPECT_EQ(contiguous_range(2, Shard{3, 4}).size(), 0U);
}

// The frames of a video job cut only at key frames (every `block` frames from the first).
std::vector<std::pair<std::size_t, std::size_t>> aligned_ranges(std::size_t total,
                                                                std::size_t block, int count) {
  std::vector<std::pair<std::size_t, std::size_t>> ranges;
  for (int index = 0; index < count; ++index) {
    const ItemRange range = aligned_range(total, block, Shard{index, count});
    ranges.emplace_back(range.begin, range.end);
  }
  return ranges;
}

TEST(Shard, AlignedRangesStartOnBlocksNearestTheEvenSplit) {
  using Ranges = std::vector<std::pair<std::size_t, std::size_t>>;
  // 81 frames with a key frame every 20 (the farm tests' video): an even split at 40.5 goes to
  // 40; in 3, 27 and 54 go to 20 and 60.
  EXPECT_EQ(aligned_ranges(81, 20, 2), (Ranges{{0, 40}, {40, 81}}));
  EXPECT_EQ(aligned_ranges(81, 20, 3), (Ranges{{0, 20}, {20, 60}, {60, 81}}));
  // The default demo, 481 frames every 60, in 2 and 4: 240.5 -> 240; 120, 240, 360 exactly.
  EXPECT_EQ(aligned_ranges(481, 60, 2), (Ranges{{0, 240}, {240, 481}}));
  EXPECT_EQ(aligned_ranges(481, 60, 4), (Ranges{{0, 120}, {120, 240}, {240, 360}, {360, 481}}));
  // Blocks of 1 are the contiguous split's balance within a frame.
  EXPECT_EQ(aligned_ranges(10, 1, 4), (Ranges{{0, 3}, {3, 5}, {5, 8}, {8, 10}}));
  // As many shards as blocks: one block each, the last one short.
  EXPECT_EQ(aligned_ranges(81, 20, 5), (Ranges{{0, 20}, {20, 40}, {40, 60}, {60, 80}, {80, 81}}));
  // Too few blocks: every shard empty.
  EXPECT_EQ(aligned_ranges(81, 20, 6), (Ranges(6, {0, 0})));
}

TEST(Shard, AlignedRangesCoverEveryItemOnceOnBlockBoundaries) {
  for (const std::size_t block : {1U, 7U, 20U, 60U}) {
    for (const std::size_t total : {1U, 19U, 20U, 61U, 481U, 1000U}) {
      const std::size_t blocks = (total + block - 1) / block;
      for (int count = 1; count <= static_cast<int>(blocks) && count <= 40; ++count) {
        const auto ranges = aligned_ranges(total, block, count);
        std::size_t next = 0;
        for (std::size_t index = 0; index < ranges.size(); ++index) {
          const auto [begin, end] = ranges[index];
          EXPECT_EQ(begin, next) << total << " in " << count << " of " << block;
          EXPECT_EQ(begin % block, 0U) << "a shard starts on a block";
          EXPECT_LT(begin, end) << "no shard is empty";
          // With at least a block a shard, each start is within half a block of the even split.
          if (total >= static_cast<std::size_t>(count) * block) {
            const double even = static_cast<double>(total * index) / static_cast<double>(count);
            EXPECT_LE(std::abs(static_cast<double>(begin) - even), 0.5 * static_cast<double>(block))
                << "shard " << index << " of " << count << ", " << total << " in " << block;
          }
          next = end;
        }
        EXPECT_EQ(next, total);
      }
    }
  }
}

TEST(Shard, StridedTakesEveryNth) {
  std::vector<std::size_t> items;
  for (std::size_t item = 0; item < 12; ++item) {
    if (in_shard(item, 12, Shard{1, 5}, ShardSplit::kStrided)) items.push_back(item);
  }
  EXPECT_THAT(items, ::testing::ElementsAre(1U, 6U, 11U));
}

TEST(Shard, SplitNamesRoundTrip) {
  for (const ShardSplit split : {ShardSplit::kContiguous, ShardSplit::kStrided}) {
    ShardSplit read =
        split == ShardSplit::kContiguous ? ShardSplit::kStrided : ShardSplit::kContiguous;
    ASSERT_TRUE(parse_split_name(split_name(split), read));
    EXPECT_EQ(read, split);
  }
  ShardSplit unused = ShardSplit::kContiguous;
  EXPECT_FALSE(parse_split_name("round-robin", unused));
}

}  // namespace
}  // namespace tumble::app
