// A hashed grid over faces' boxes (face_grid.hpp).
//
// Layout: cells are hashed; the entries are partitioned by the hash of their block of 16^3
// cells, so that each partition stays spatially coherent (the faces it reads are near each
// other in memory for meshes written in any local order); each partition is then sorted by
// cell hash into buckets on its own, in cache, and its cells visited. Partitions are taken by
// the threads in turn.
#include "face_grid.hpp"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace tumble::engine::detail {
namespace {

constexpr int kBlockShift = 4;         // a partition holds whole blocks of 16^3 cells
constexpr double kCellLimit = 0x1p30;  // cell coordinates are clamped to +-2^30
constexpr std::size_t kEntriesPerBucket = 4;

/// The cell coordinate of `v` where cells are 1 / inverse wide: monotone in v.
std::int32_t to_cell(float v, double inverse) {
  const double scaled = std::clamp(static_cast<double>(v) * inverse, -kCellLimit, kCellLimit);
  const auto truncated = static_cast<std::int32_t>(scaled);
  return truncated - (scaled < static_cast<double>(truncated) ? 1 : 0);  // floor
}

bool spans_at_most_two(const CellRange& range) {
  return range.high[0] - range.low[0] <= 1 && range.high[1] - range.low[1] <= 1 &&
         range.high[2] - range.low[2] <= 1;
}

std::size_t partition_of(const GridCell& c, int bits) {
  return grid_cell_hash(c.level, c.x >> kBlockShift, c.y >> kBlockShift, c.z >> kBlockShift) >>
         (32 - bits);
}

}  // namespace

std::uint32_t grid_cell_hash(std::int32_t level, std::int32_t x, std::int32_t y, std::int32_t z) {
  const auto u = [](std::int32_t v) {
    return static_cast<std::uint64_t>(static_cast<std::uint32_t>(v));
  };
  std::uint64_t h = (u(x) << 32 | u(y)) ^ ((u(z) << 8 | u(level)) * 0x9e3779b97f4a7c15ull);
  h ^= h >> 32;
  h *= 0xd6e8feb86659fd93ull;
  h ^= h >> 32;
  h *= 0xd6e8feb86659fd93ull;
  h ^= h >> 32;
  return static_cast<std::uint32_t>(h);
}

/// One thread's scratch memory while visiting.
struct FaceGrid::Scratch {
  std::vector<Entry> entries;
  std::vector<std::uint32_t> cursor;
  std::vector<GridItem> items;
};

FaceGrid::FaceGrid(const std::vector<FloatBox>& boxes, const std::vector<std::uint8_t>& include,
                   double inverse_cell, int levels, unsigned threads)
    : boxes_(boxes),
      include_(include),
      threads_(std::max(1u, threads)),
      max_levels_(std::clamp(levels, 1, kMaxLevels)),
      level_(boxes.size(), kOutside) {
  if (boxes.size() > kFaceMask) throw std::length_error("FaceGrid: more than 2^29 - 1 faces");
  for (int level = 0; level < max_levels_; ++level) {
    inverses_.push_back(std::ldexp(inverse_cell, -level));
  }
  std::vector<std::array<std::size_t, kPartitions>> counts(threads_);
  std::vector<std::vector<std::uint32_t>> oversized(threads_);
  std::vector<std::vector<bool>> populated(threads_, std::vector<bool>(max_levels_));
  for (auto& count : counts) count.fill(0);
  on_threads(threads_, [&](unsigned thread) {
    place(thread, counts[thread], oversized[thread], populated[thread]);
  });
  for (unsigned thread = 0; thread < threads_; ++thread) {
    oversized_.insert(oversized_.end(), oversized[thread].begin(), oversized[thread].end());
  }
  for (int level = 0; level < max_levels_; ++level) {
    for (unsigned thread = 0; thread < threads_; ++thread) {
      if (populated[thread][static_cast<std::size_t>(level)]) {
        levels_.push_back(level);
        break;
      }
    }
  }
  lay_out(counts);
  on_threads(threads_, [&](unsigned thread) { scatter(thread, cursors_[thread]); });
}

std::pair<std::size_t, std::size_t> FaceGrid::slice(unsigned thread) const {
  const std::size_t n = boxes_.size();
  return {n * thread / threads_, n * (thread + 1) / threads_};
}

CellRange FaceGrid::cells(const FloatBox& box, std::int32_t level) const {
  const double inverse = this->inverse(level);
  CellRange range;
  for (int axis = 0; axis < 3; ++axis) {
    range.low[axis] = to_cell(box.lo[axis], inverse);
    range.high[axis] = to_cell(box.hi[axis], inverse);
  }
  return range;
}

/// Each included face's level, the first on which its box spans at most two cells along each
/// axis (the extent over the cell size gives it but for rounding, checked here), and its
/// entries counted per partition.
void FaceGrid::place(unsigned thread, std::array<std::size_t, kPartitions>& counts,
                     std::vector<std::uint32_t>& oversized, std::vector<bool>& populated) {
  const auto [first, last] = slice(thread);
  for (std::size_t t = first; t < last; ++t) {
    if (include_[t] == 0) continue;
    const FloatBox& box = boxes_[t];
    const double extent = std::max({static_cast<double>(box.hi[0]) - box.lo[0],
                                    static_cast<double>(box.hi[1]) - box.lo[1],
                                    static_cast<double>(box.hi[2]) - box.lo[2]});
    const double cells = extent * inverses_[0];
    int level = max_levels_;
    if (cells <= 1.0) {
      level = 0;
    } else if (cells < 0x1p200) {
      level = std::ilogb(cells) + 1;
    }
    CellRange range;
    for (; level < max_levels_; ++level) {
      range = this->cells(box, level);
      if (spans_at_most_two(range)) break;
    }
    if (level >= max_levels_) {
      oversized.push_back(static_cast<std::uint32_t>(t));
      continue;
    }
    level_[t] = static_cast<std::uint8_t>(level);
    populated[static_cast<std::size_t>(level)] = true;
    for (std::int32_t x = range.low[0]; x <= range.high[0]; ++x) {
      for (std::int32_t y = range.low[1]; y <= range.high[1]; ++y) {
        for (std::int32_t z = range.low[2]; z <= range.high[2]; ++z) {
          ++counts[partition_of({level, x, y, z}, kPartitionBits)];
        }
      }
    }
  }
}

/// Where each thread writes each partition's entries, and the partitions' buckets.
void FaceGrid::lay_out(const std::vector<std::array<std::size_t, kPartitions>>& counts) {
  cursors_.resize(threads_);
  std::size_t offset = 0;
  for (std::size_t p = 0; p < kPartitions; ++p) {
    partition_start_[p] = offset;
    for (unsigned thread = 0; thread < threads_; ++thread) {
      cursors_[thread][p] = offset;
      offset += counts[thread][p];
    }
  }
  partition_start_[kPartitions] = offset;
  if (offset >= std::numeric_limits<std::uint32_t>::max()) {
    throw std::length_error("FaceGrid: more than 2^32 - 1 entries");
  }
  entries_ = std::make_unique_for_overwrite<Entry[]>(offset);
  std::size_t buckets = 0;
  for (std::size_t p = 0; p < kPartitions; ++p) {
    first_bucket_[p] = buckets;
    const std::size_t count = partition_start_[p + 1] - partition_start_[p];
    buckets += std::bit_ceil(std::max<std::size_t>(1, count / kEntriesPerBucket)) + 1;
  }
  first_bucket_[kPartitions] = buckets;
  bucket_start_.resize(buckets);
}

void FaceGrid::scatter(unsigned thread, std::array<std::size_t, kPartitions>& cursor) {
  const auto [first, last] = slice(thread);
  Entry* const entries = entries_.get();
  for (std::size_t t = first; t < last; ++t) {
    if (level_[t] == kOutside) continue;
    const std::int32_t level = level_[t];
    const CellRange range = cells(boxes_[t], level);
    for (std::int32_t x = range.low[0]; x <= range.high[0]; ++x) {
      for (std::int32_t y = range.low[1]; y <= range.high[1]; ++y) {
        for (std::int32_t z = range.low[2]; z <= range.high[2]; ++z) {
          const auto corner = static_cast<std::uint32_t>(
              (x - range.low[0]) | (y - range.low[1]) << 1 | (z - range.low[2]) << 2);
          entries[cursor[partition_of({level, x, y, z}, kPartitionBits)]++] = {
              grid_cell_hash(level, x, y, z),
              static_cast<std::uint32_t>(t) | corner << kCornerShift};
        }
      }
    }
  }
}

GridCell FaceGrid::cell_of(const Entry& entry) const {
  const std::uint32_t face = entry.face_corner & kFaceMask;
  const std::uint32_t corner = entry.face_corner >> kCornerShift;
  const std::int32_t level = level_[face];
  const double inverse = this->inverse(level);
  const FloatBox& box = boxes_[face];
  return {level, to_cell(box.lo[0], inverse) + static_cast<std::int32_t>(corner & 1u),
          to_cell(box.lo[1], inverse) + static_cast<std::int32_t>(corner >> 1 & 1u),
          to_cell(box.lo[2], inverse) + static_cast<std::int32_t>(corner >> 2 & 1u)};
}

/// Sorts a partition's entries into buckets by cell hash, then visits each bucket's cells.
void FaceGrid::sort_partition(std::size_t p, unsigned thread, Scratch& scratch,
                              CellVisitor& visitor) {
  const std::size_t begin = partition_start_[p], count = partition_start_[p + 1] - begin;
  const std::size_t buckets = first_bucket_[p + 1] - first_bucket_[p] - 1;
  std::uint32_t* const start = bucket_start_.data() + first_bucket_[p];
  Entry* const entries = entries_.get() + begin;
  std::fill(start, start + buckets + 1, 0u);
  const auto mask = static_cast<std::uint32_t>(buckets - 1);
  for (std::size_t i = 0; i < count; ++i) ++start[(entries[i].hash & mask) + 1];
  for (std::size_t b = 0; b < buckets; ++b) start[b + 1] += start[b];
  scratch.cursor.assign(start, start + buckets);
  scratch.entries.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    scratch.entries[scratch.cursor[entries[i].hash & mask]++] = entries[i];
  }
  std::copy_n(scratch.entries.begin(), count, entries);
  std::vector<GridItem>& items = scratch.items;
  for (std::size_t b = 0; b < buckets; ++b) {
    if (start[b + 1] == start[b]) continue;
    items.clear();
    bool one_cell = true;
    for (std::uint32_t e = start[b]; e < start[b + 1]; ++e) {
      const std::uint32_t face = entries[e].face_corner & kFaceMask;
      items.push_back(
          {cell_of(entries[e]), boxes_[face], face, entries[e].face_corner >> kCornerShift});
      one_cell &= items.back().cell == items.front().cell;
    }
    if (!one_cell) {
      std::sort(items.begin(), items.end(),
                [](const GridItem& a, const GridItem& c) { return a.cell < c.cell; });
    }
    for (std::size_t run = 0; run < items.size();) {
      std::size_t end = run + 1;
      while (end < items.size() && items[end].cell == items[run].cell) ++end;
      visitor.visit(thread, std::span<const GridItem>(items.data() + run, end - run));
      run = end;
    }
  }
  for (std::size_t b = 0; b <= buckets; ++b) start[b] += static_cast<std::uint32_t>(begin);
}

void FaceGrid::visit(CellVisitor& visitor) {
  std::atomic<std::size_t> next{0};
  std::vector<Scratch> scratch(threads_);
  on_threads(threads_, [&](unsigned thread) {
    for (std::size_t p; (p = next.fetch_add(1)) < kPartitions;) {
      sort_partition(p, thread, scratch[thread], visitor);
    }
  });
}

std::pair<const FaceGrid::Entry*, const FaceGrid::Entry*> FaceGrid::bucket(
    const GridCell& cell) const {
  const std::size_t p = partition_of(cell, kPartitionBits);
  const std::size_t buckets = first_bucket_[p + 1] - first_bucket_[p] - 1;
  const std::uint32_t* start = bucket_start_.data() + first_bucket_[p] +
                               (grid_cell_hash(cell.level, cell.x, cell.y, cell.z) & (buckets - 1));
  return {entries_.get() + start[0], entries_.get() + start[1]};
}

}  // namespace tumble::engine::detail
