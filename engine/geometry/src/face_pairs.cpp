// Face pairs by a hashed grid over the faces' boxes, judged by a certified filter
// (face_pairs.hpp).
//
// Design.
// - Candidates: a uniform grid of cell size c (twice the median extent of a sample of faces)
//   holds each face in every cell its box touches. A face whose box spans more than two cells
//   along an axis goes to a coarser level (cells 2c, 4c, ...) where it spans at most two, so a
//   face is in at most eight cells (on the benchmark's torus, 3.4 on average). Two faces of one
//   level whose boxes overlap share the cell of the low corner of their boxes' intersection;
//   the pair is judged there only: in a cell, each entry knows along which axes the cell is one
//   past its face's lowest cell (three bits), and the pair belongs to the cell exactly when no
//   axis has the bit set for both. A face on a finer level looks itself up in the cells of the
//   coarser levels, with the same rule. So every pair of faces whose boxes overlap is judged
//   once, whatever the cell size; the cell size only decides the speed.
// - Layout: cells are hashed; the entries are partitioned by the hash of their block of 16^3
//   cells (so each partition stays spatially coherent: the faces it reads are near each other
//   in memory for meshes written in any local order), then each partition is sorted by cell
//   hash into buckets on its own, in cache. Partitions are taken by the threads in turn.
// - Judging: the vertex indices two faces share say which test applies (face_pairs.hpp);
//   orientation signs come from certified_orientation.hpp; what they leave open goes to
//   ExactFaceTests. Counts are summed per thread and added up at the end, so the result does
//   not depend on the number of threads.
#include "face_pairs.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <exception>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <thread>

#include "certified_orientation.hpp"

namespace tumble::engine::detail {
namespace {

using Face = std::array<std::uint32_t, 3>;

constexpr int kPartitionBits = 8;
constexpr std::size_t kPartitions = std::size_t{1} << kPartitionBits;
constexpr int kBlockShift = 4;    // a partition holds whole blocks of 16^3 cells
constexpr int kCornerShift = 29;  // an entry's face and corner bits: face | corner << 29
constexpr std::uint32_t kFaceMask = (std::uint32_t{1} << kCornerShift) - 1;
constexpr double kCellLimit = 0x1p30;  // cell coordinates are clamped to +-2^30
constexpr int kLevels = 250;           // cell sizes c, 2c, ..., 2^249 c
constexpr std::uint8_t kWide = 254;    // a face spanning more than two cells on every level
constexpr std::uint8_t kNoLevel = 255;  // a collinear face: in no cell
constexpr double kCellsPerExtent = 2.0;  // cell size over the sampled median extent
constexpr std::size_t kEntriesPerBucket = 4;

/// The next float below (above) a finite or infinite float, toward -inf (+inf).
float float_before(float f) {
  if (f == 0.0f) return -std::numeric_limits<float>::denorm_min();
  const auto bits = std::bit_cast<std::uint32_t>(f);
  return std::bit_cast<float>(f > 0.0f ? bits - 1 : bits + 1);
}
float float_after(float f) {
  if (f == 0.0f) return std::numeric_limits<float>::denorm_min();
  const auto bits = std::bit_cast<std::uint32_t>(f);
  return std::bit_cast<float>(f > 0.0f ? bits + 1 : bits - 1);
}

/// The largest float not above `x`, and the smallest not below it.
float float_down(double x) {
  const auto f = static_cast<float>(x);
  return static_cast<double>(f) <= x ? f : float_before(f);
}
float float_up(double x) {
  const auto f = static_cast<float>(x);
  return static_cast<double>(f) >= x ? f : float_after(f);
}

struct Cell {
  std::int32_t level, x, y, z;
  auto operator<=>(const Cell&) const = default;
};

/// A 32-bit hash of a cell (multiply-xorshift rounds).
std::uint32_t cell_hash(std::int32_t level, std::int32_t x, std::int32_t y, std::int32_t z) {
  const auto u = [](std::int32_t v) { return static_cast<std::uint64_t>(static_cast<std::uint32_t>(v)); };
  std::uint64_t h = (u(x) << 32 | u(y)) ^ ((u(z) << 8 | u(level)) * 0x9e3779b97f4a7c15ull);
  h ^= h >> 32;
  h *= 0xd6e8feb86659fd93ull;
  h ^= h >> 32;
  h *= 0xd6e8feb86659fd93ull;
  h ^= h >> 32;
  return static_cast<std::uint32_t>(h);
}

std::uint32_t cell_hash(const Cell& c) {
  return cell_hash(c.level, c.x, c.y, c.z);
}

/// The partition of a cell: that of its block of 16^3 cells.
std::size_t partition_of(const Cell& c) {
  return cell_hash(c.level, c.x >> kBlockShift, c.y >> kBlockShift, c.z >> kBlockShift) >>
         (32 - kPartitionBits);
}

/// The cell coordinate of `v` where cells are 1 / inverse wide: monotone in v.
std::int32_t to_cell(float v, double inverse) {
  const double scaled = std::floor(static_cast<double>(v) * inverse);
  return static_cast<std::int32_t>(std::clamp(scaled, -kCellLimit, kCellLimit));
}

/// The cells a box touches on one level: [low, high] along each axis.
struct CellRange {
  std::array<std::int32_t, 3> low, high;
};

CellRange cell_range(const FloatBox& box, double inverse) {
  CellRange range;
  for (int axis = 0; axis < 3; ++axis) {
    range.low[axis] = to_cell(box.lo[axis], inverse);
    range.high[axis] = to_cell(box.hi[axis], inverse);
  }
  return range;
}

bool spans_at_most_two(const CellRange& range) {
  return range.high[0] - range.low[0] <= 1 && range.high[1] - range.low[1] <= 1 &&
         range.high[2] - range.low[2] <= 1;
}

bool boxes_overlap(const FloatBox& a, const FloatBox& b) {
  return a.lo[0] <= b.hi[0] && b.lo[0] <= a.hi[0] && a.lo[1] <= b.hi[1] && b.lo[1] <= a.hi[1] &&
         a.lo[2] <= b.hi[2] && b.lo[2] <= a.hi[2];
}

/// An entry of the grid: a face in one of its cells.
struct Entry {
  std::uint32_t hash;         ///< of the cell
  std::uint32_t face_corner;  ///< face | corner << kCornerShift
};

/// An entry of one bucket, with its cell and box at hand.
struct Item {
  Cell cell;
  FloatBox box;
  std::uint32_t face;
  std::uint32_t corner;  ///< bit a: the cell is one past the face's lowest cell along axis a
};

/// One thread's counts and scratch memory.
struct Tally {
  std::vector<PartPairCounts> parts;
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> meeting;
  std::size_t candidates = 0, deferred = 0, deferred_faces = 0;
  std::array<std::size_t, kPartitions> partition_entries{};
  std::array<bool, kLevels> levels{};
  std::vector<std::uint32_t> wide;
  std::vector<Entry> scratch;
  std::vector<std::uint32_t> cursor;
  std::vector<Item> items;
};

/// What the filter can tell: certainly not, certainly, or not at all.
enum class Filtered { kNo, kYes, kUnknown };

/// Runs work(thread) on `threads` threads (this one is thread 0), rethrowing the first error.
template <typename Work>
void on_threads(unsigned threads, const Work& work) {
  std::vector<std::exception_ptr> errors(threads);
  const auto guarded = [&](unsigned thread) {
    try {
      work(thread);
    } catch (...) {
      errors[thread] = std::current_exception();
    }
  };
  std::vector<std::thread> pool;
  for (unsigned thread = 1; thread < threads; ++thread) pool.emplace_back(guarded, thread);
  guarded(0);
  for (std::thread& thread : pool) thread.join();
  for (const std::exception_ptr& error : errors) {
    if (error) std::rethrow_exception(error);
  }
}

class PairSearch {
 public:
  PairSearch(const TriangleMesh& mesh, const std::vector<std::uint32_t>& triangle_part,
             std::size_t parts, const ExactFaceTests& exact, const FacePairOptions& options);
  FacePairs run();

 private:
  std::pair<std::size_t, std::size_t> slice(unsigned thread) const {
    const std::size_t n = faces_.size();
    return {n * thread / threads_, n * (thread + 1) / threads_};
  }
  void choose_cell_size();
  void prepare(unsigned thread);
  void prepare_face(std::uint32_t t, Tally& tally);
  void place_face(std::uint32_t t, Tally& tally);
  void lay_out();
  void scatter(unsigned thread);
  void sort_partition(std::size_t partition, Tally& tally);
  void pair_bucket(const Entry* begin, const Entry* end, Tally& tally) const;
  void cross_levels(unsigned thread);
  void look_up(std::uint32_t t, std::int32_t level, Tally& tally) const;
  void wide_faces(unsigned thread);
  void judge(std::uint32_t t, std::uint32_t u, Tally& tally) const;
  std::optional<PairVerdict> filtered(std::uint32_t t, std::uint32_t u) const;
  Filtered straddle(const Face& a, unsigned skip, std::uint32_t plane_face) const;
  Filtered edge_meets(std::uint32_t p, std::uint32_t q, std::uint32_t face) const;
  Filtered edges_meet(std::uint32_t t, std::uint32_t u, int shared, int corner_a,
                      int corner_b) const;
  bool one_side(std::uint32_t corners_face, std::uint32_t plane_face) const;
  FacePairs total();

  double inverse(std::int32_t level) const { return inverses_[static_cast<std::size_t>(level)]; }
  Cell cell_of(const Entry& entry) const;

  const std::vector<Eigen::Vector3d>& positions_;
  const std::vector<Face>& faces_;
  const std::vector<std::uint32_t>& part_;
  const std::size_t parts_;
  const ExactFaceTests& exact_;
  const FacePairOptions options_;
  const unsigned threads_;
  double inverse_cell_ = 1.0;  ///< 1 / c, level 0
  std::array<double, kLevels> inverses_{};  ///< 1 / (2^level c)
  std::vector<FacePlane> planes_;
  std::vector<FloatBox> boxes_;
  std::vector<std::uint8_t> level_;
  std::vector<std::uint8_t> in_range_;  ///< 1 when the filter may judge the face
  std::vector<std::uint8_t> collinear_;
  std::vector<Tally> tallies_;
  std::vector<std::int32_t> levels_;  ///< the levels holding faces, ascending
  std::vector<std::uint32_t> wide_;
  std::unique_ptr<Entry[]> entries_;
  std::array<std::size_t, kPartitions + 1> partition_start_{};
  std::array<std::size_t, kPartitions + 1> first_bucket_{};
  std::vector<std::uint32_t> bucket_start_;  ///< per partition: its buckets' starts, then its end
  std::vector<std::array<std::size_t, kPartitions>> cursors_;  ///< per thread, for scatter
};

PairSearch::PairSearch(const TriangleMesh& mesh, const std::vector<std::uint32_t>& triangle_part,
                       std::size_t parts, const ExactFaceTests& exact,
                       const FacePairOptions& options)
    : positions_(mesh.positions),
      faces_(mesh.triangles),
      part_(triangle_part),
      parts_(parts),
      exact_(exact),
      options_(options),
      // Small meshes on one thread: starting threads would cost more than it saves.
      threads_(static_cast<unsigned>(std::clamp<std::size_t>(mesh.triangles.size() / 8192, 1,
                                                              std::max(1u, options.threads)))) {
  if (faces_.size() > kFaceMask) {
    throw std::length_error("find_face_pairs: more than 2^29 - 1 faces");
  }
  tallies_.resize(threads_);
  for (Tally& tally : tallies_) tally.parts.resize(parts_);
}

/// The level-0 cell: twice the median extent of up to 1024 faces spread over the mesh.
void PairSearch::choose_cell_size() {
  std::vector<double> extents;
  const std::size_t n = faces_.size(), samples = std::min<std::size_t>(n, 1024);
  for (std::size_t i = 0; i < samples; ++i) {
    const Face& f = faces_[i * n / samples];
    const Eigen::Vector3d& a = positions_[f[0]];
    const Eigen::Vector3d low = a.cwiseMin(positions_[f[1]]).cwiseMin(positions_[f[2]]);
    const Eigen::Vector3d high = a.cwiseMax(positions_[f[1]]).cwiseMax(positions_[f[2]]);
    const double extent = (high - low).maxCoeff();
    if (std::isfinite(extent) && extent > 0.0) extents.push_back(extent);
  }
  double cell = 1.0;
  if (!extents.empty()) {
    const auto middle = extents.begin() + static_cast<std::ptrdiff_t>(extents.size() / 2);
    std::nth_element(extents.begin(), middle, extents.end());
    cell = kCellsPerExtent * *middle;
  }
  inverse_cell_ = 1.0 / cell;
  if (!std::isfinite(inverse_cell_) || inverse_cell_ <= 0.0) inverse_cell_ = 1.0;
  for (int level = 0; level < kLevels; ++level) {
    inverses_[static_cast<std::size_t>(level)] = std::ldexp(inverse_cell_, -level);
  }
}

FloatBox box_of(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  FloatBox box;
  for (int axis = 0; axis < 3; ++axis) {
    box.lo[axis] = float_down(std::min({a[axis], b[axis], c[axis]}));
    box.hi[axis] = float_up(std::max({a[axis], b[axis], c[axis]}));
  }
  return box;
}

/// A face's plane, box, collinearity and level, and its entries counted per partition.
void PairSearch::prepare_face(std::uint32_t t, Tally& tally) {
  const Face& f = faces_[t];
  const Eigen::Vector3d &o = positions_[f[0]], &a = positions_[f[1]], &b = positions_[f[2]];
  bool not_collinear = false;
  planes_[t] = face_plane(o, a, b, not_collinear);
  bool in_range = true;
  for (const Eigen::Vector3d* p : {&o, &a, &b}) {
    in_range &= in_filter_range(p->x()) && in_filter_range(p->y()) && in_filter_range(p->z());
  }
  in_range_[t] = in_range ? 1 : 0;
  if (!(options_.filter && in_range && not_collinear)) {
    ++tally.deferred_faces;
    not_collinear = !exact_.collinear(t);
  }
  collinear_[t] = not_collinear ? 0 : 1;
  if (!not_collinear) {
    level_[t] = kNoLevel;
    return;
  }
  boxes_[t] = box_of(o, a, b);
  place_face(t, tally);
}

/// The coarsest needed level: the first on which the face's box spans at most two cells along
/// each axis (the extent over the cell size gives it but for rounding, checked here).
void PairSearch::place_face(std::uint32_t t, Tally& tally) {
  const FloatBox& box = boxes_[t];
  const double extent = std::max({static_cast<double>(box.hi[0]) - box.lo[0],
                                  static_cast<double>(box.hi[1]) - box.lo[1],
                                  static_cast<double>(box.hi[2]) - box.lo[2]});
  const double cells = extent * inverse_cell_;
  int level = kLevels;
  if (cells <= 1.0) {
    level = 0;
  } else if (cells < 0x1p200) {
    level = std::ilogb(cells) + 1;
  }
  CellRange range;
  for (; level < kLevels; ++level) {
    range = cell_range(box, inverse(level));
    if (spans_at_most_two(range)) break;
  }
  if (level >= kLevels) {
    level_[t] = kWide;
    tally.wide.push_back(t);
    return;
  }
  level_[t] = static_cast<std::uint8_t>(level);
  tally.levels[static_cast<std::size_t>(level)] = true;
  for (std::int32_t x = range.low[0]; x <= range.high[0]; ++x) {
    for (std::int32_t y = range.low[1]; y <= range.high[1]; ++y) {
      for (std::int32_t z = range.low[2]; z <= range.high[2]; ++z) {
        ++tally.partition_entries[partition_of({level, x, y, z})];
      }
    }
  }
}

void PairSearch::prepare(unsigned thread) {
  const auto [first, last] = slice(thread);
  Tally& tally = tallies_[thread];
  for (std::size_t t = first; t < last; ++t) prepare_face(static_cast<std::uint32_t>(t), tally);
}

/// Where each thread writes each partition's entries, and the partitions' buckets.
void PairSearch::lay_out() {
  cursors_.resize(threads_);
  std::size_t offset = 0;
  for (std::size_t p = 0; p < kPartitions; ++p) {
    partition_start_[p] = offset;
    for (unsigned thread = 0; thread < threads_; ++thread) {
      cursors_[thread][p] = offset;
      offset += tallies_[thread].partition_entries[p];
    }
  }
  partition_start_[kPartitions] = offset;
  if (offset >= std::numeric_limits<std::uint32_t>::max()) {
    throw std::length_error("find_face_pairs: more than 2^32 - 1 grid entries");
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
  for (const Tally& tally : tallies_) {
    for (std::size_t level = 0; level < kLevels; ++level) {
      if (tally.levels[level]) levels_.push_back(static_cast<std::int32_t>(level));
    }
    wide_.insert(wide_.end(), tally.wide.begin(), tally.wide.end());
  }
  std::sort(levels_.begin(), levels_.end());
  levels_.erase(std::unique(levels_.begin(), levels_.end()), levels_.end());
  std::sort(wide_.begin(), wide_.end());
}

void PairSearch::scatter(unsigned thread) {
  const auto [first, last] = slice(thread);
  std::array<std::size_t, kPartitions>& cursor = cursors_[thread];
  Entry* const entries = entries_.get();
  for (std::size_t t = first; t < last; ++t) {
    const std::int32_t level = level_[t];
    if (level >= kWide) continue;
    const CellRange range = cell_range(boxes_[t], inverse(level));
    for (std::int32_t x = range.low[0]; x <= range.high[0]; ++x) {
      for (std::int32_t y = range.low[1]; y <= range.high[1]; ++y) {
        for (std::int32_t z = range.low[2]; z <= range.high[2]; ++z) {
          const Cell cell{level, x, y, z};
          const auto corner = static_cast<std::uint32_t>((x - range.low[0]) |
                                                         (y - range.low[1]) << 1 |
                                                         (z - range.low[2]) << 2);
          entries[cursor[partition_of(cell)]++] = {
              cell_hash(cell), static_cast<std::uint32_t>(t) | corner << kCornerShift};
        }
      }
    }
  }
}

Cell PairSearch::cell_of(const Entry& entry) const {
  const std::uint32_t face = entry.face_corner & kFaceMask;
  const std::uint32_t corner = entry.face_corner >> kCornerShift;
  const std::int32_t level = level_[face];
  const double scale = inverse(level);
  const FloatBox& box = boxes_[face];
  return {level, to_cell(box.lo[0], scale) + static_cast<std::int32_t>(corner & 1u),
          to_cell(box.lo[1], scale) + static_cast<std::int32_t>(corner >> 1 & 1u),
          to_cell(box.lo[2], scale) + static_cast<std::int32_t>(corner >> 2 & 1u)};
}

/// Sorts a partition's entries into buckets by cell hash, then judges each bucket's pairs.
void PairSearch::sort_partition(std::size_t p, Tally& tally) {
  const std::size_t begin = partition_start_[p], count = partition_start_[p + 1] - begin;
  const std::size_t buckets = first_bucket_[p + 1] - first_bucket_[p] - 1;
  std::uint32_t* const start = bucket_start_.data() + first_bucket_[p];
  Entry* const entries = entries_.get() + begin;
  std::fill(start, start + buckets + 1, 0u);
  const std::uint32_t mask = static_cast<std::uint32_t>(buckets - 1);
  for (std::size_t i = 0; i < count; ++i) ++start[(entries[i].hash & mask) + 1];
  for (std::size_t b = 0; b < buckets; ++b) start[b + 1] += start[b];
  tally.cursor.assign(start, start + buckets);
  tally.scratch.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    tally.scratch[tally.cursor[entries[i].hash & mask]++] = entries[i];
  }
  std::copy(tally.scratch.begin(), tally.scratch.begin() + static_cast<std::ptrdiff_t>(count),
            entries);
  for (std::size_t b = 0; b < buckets; ++b) {
    if (start[b + 1] - start[b] >= 2) pair_bucket(entries + start[b], entries + start[b + 1], tally);
  }
  for (std::size_t b = 0; b <= buckets; ++b) start[b] += static_cast<std::uint32_t>(begin);
}

/// Judges the pairs of faces that share a cell of this bucket and belong to it.
void PairSearch::pair_bucket(const Entry* begin, const Entry* end, Tally& tally) const {
  std::vector<Item>& items = tally.items;
  items.clear();
  bool one_cell = true;
  for (const Entry* e = begin; e != end; ++e) {
    const std::uint32_t face = e->face_corner & kFaceMask;
    items.push_back({cell_of(*e), boxes_[face], face, e->face_corner >> kCornerShift});
    one_cell &= items.back().cell == items.front().cell;
  }
  if (!one_cell) {
    std::sort(items.begin(), items.end(),
              [](const Item& a, const Item& b) { return a.cell < b.cell; });
  }
  for (std::size_t run = 0; run < items.size();) {
    std::size_t run_end = run + 1;
    while (run_end < items.size() && items[run_end].cell == items[run].cell) ++run_end;
    for (std::size_t i = run; i < run_end; ++i) {
      for (std::size_t j = i + 1; j < run_end; ++j) {
        if ((items[i].corner & items[j].corner) != 0) continue;
        if (boxes_overlap(items[i].box, items[j].box)) judge(items[i].face, items[j].face, tally);
      }
    }
    run = run_end;
  }
}

/// Faces on a finer level than others: each looks itself up on every coarser level.
void PairSearch::cross_levels(unsigned thread) {
  const auto [first, last] = slice(thread);
  Tally& tally = tallies_[thread];
  for (std::size_t t = first; t < last; ++t) {
    if (level_[t] >= kWide) continue;
    for (const std::int32_t level : levels_) {
      if (level > level_[t]) look_up(static_cast<std::uint32_t>(t), level, tally);
    }
  }
}

/// Judges face t against the faces of `level` in the cells its box touches there: a pair
/// belongs to the cell of the low corner of the boxes' intersection.
void PairSearch::look_up(std::uint32_t t, std::int32_t level, Tally& tally) const {
  const FloatBox& box = boxes_[t];
  const CellRange range = cell_range(box, inverse(level));
  for (std::int32_t x = range.low[0]; x <= range.high[0]; ++x) {
    for (std::int32_t y = range.low[1]; y <= range.high[1]; ++y) {
      for (std::int32_t z = range.low[2]; z <= range.high[2]; ++z) {
        const Cell cell{level, x, y, z};
        const std::size_t p = partition_of(cell);
        const std::size_t buckets = first_bucket_[p + 1] - first_bucket_[p] - 1;
        const std::uint32_t* start =
            bucket_start_.data() + first_bucket_[p] + (cell_hash(cell) & (buckets - 1));
        for (std::uint32_t e = start[0]; e < start[1]; ++e) {
          const Entry& entry = entries_[e];
          const std::uint32_t u = entry.face_corner & kFaceMask;
          const std::uint32_t corner = entry.face_corner >> kCornerShift;
          if (level_[u] != level || !(cell_of(entry) == cell)) continue;
          // The low corner of the intersection is in this cell along each axis.
          const bool owns = (x == range.low[0] || (corner & 1u) == 0) &&
                            (y == range.low[1] || (corner & 2u) == 0) &&
                            (z == range.low[2] || (corner & 4u) == 0);
          if (owns && boxes_overlap(box, boxes_[u])) judge(t, u, tally);
        }
      }
    }
  }
}

/// Faces too large for every level (coordinates near the float range): against every face.
void PairSearch::wide_faces(unsigned thread) {
  Tally& tally = tallies_[thread];
  for (std::size_t w = thread; w < wide_.size(); w += threads_) {
    const std::uint32_t t = wide_[w];
    for (std::uint32_t u = 0; u < faces_.size(); ++u) {
      if (u == t || level_[u] == kNoLevel || (level_[u] == kWide && u < t)) continue;
      if (boxes_overlap(boxes_[t], boxes_[u])) judge(t, u, tally);
    }
  }
}

/// Whether the corners of `a` outside the mask `skip` lie on both sides of the plane of
/// `plane_face` (corners on it count for neither side), as far as the filter can tell.
Filtered PairSearch::straddle(const Face& a, unsigned skip, std::uint32_t plane_face) const {
  const FacePlane& plane = planes_[plane_face];
  const Eigen::Vector3d& o = positions_[faces_[plane_face][0]];
  bool positive = false, negative = false, unknown = false;
  for (unsigned i = 0; i < 3; ++i) {
    if ((skip >> i & 1u) != 0) continue;
    const int side = certified_side(plane, o, positions_[a[i]]);
    positive |= side > 0;
    negative |= side < 0;
    unknown |= side == 0;
  }
  if (positive && negative) return Filtered::kYes;
  if ((positive || unknown) && (negative || unknown)) return Filtered::kUnknown;
  return Filtered::kNo;
}

/// Whether all corners of `corners_face` lie certainly and strictly on one side of the plane
/// of `plane_face`: then the two faces do not meet.
bool PairSearch::one_side(std::uint32_t corners_face, std::uint32_t plane_face) const {
  const FacePlane& plane = planes_[plane_face];
  const Eigen::Vector3d& o = positions_[faces_[plane_face][0]];
  const Face& f = faces_[corners_face];
  const int first = certified_side(plane, o, positions_[f[0]]);
  return first != 0 && certified_side(plane, o, positions_[f[1]]) == first &&
         certified_side(plane, o, positions_[f[2]]) == first;
}

/// The verdict where the filter can give it (part_overlap.cpp's tests, in their order).
std::optional<PairVerdict> PairSearch::filtered(std::uint32_t t, std::uint32_t u) const {
  if (in_range_[t] == 0 || in_range_[u] == 0) return std::nullopt;
  if (part_[t] != part_[u]) {
    if (one_side(u, t) || one_side(t, u)) return PairVerdict::kApart;
    return std::nullopt;
  }
  const Face &a = faces_[t], &b = faces_[u];
  unsigned a_in_b = 0, b_in_a = 0;
  int shared = 0, corner_a = 0, corner_b = 0;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (a[i] != b[j]) continue;
      if (shared++ == 0) corner_a = i, corner_b = j;
      a_in_b |= 1u << i;
      b_in_a |= 1u << j;
    }
  }
  if (shared == 3) {
    const bool same = a[(corner_a + 1) % 3] == b[(corner_b + 1) % 3];
    return same ? PairVerdict::kRepeated : PairVerdict::kMirrored;
  }
  if (shared == 2) return PairVerdict::kApart;
  // Crossing needs corners strictly on both sides of each face's plane.
  const Filtered a_straddles = straddle(a, a_in_b, u);
  if (a_straddles == Filtered::kNo) return PairVerdict::kApart;
  const Filtered b_straddles = straddle(b, b_in_a, t);
  if (b_straddles == Filtered::kNo) return PairVerdict::kApart;
  // And an edge of one meeting the other.
  const Filtered meet = edges_meet(t, u, shared, corner_a, corner_b);
  if (meet == Filtered::kNo) return PairVerdict::kApart;
  if (meet == Filtered::kYes && a_straddles == Filtered::kYes && b_straddles == Filtered::kYes) {
    return PairVerdict::kCrossing;
  }
  return std::nullopt;
}

/// Whether the segment between vertices p and q meets face `face` (closed). The line through
/// them meets it where the orientations of (p, q) with its three edges agree in sign (zero
/// included), and misses it where two have opposite signs; the segment meets it where the
/// line does and p and q lie on opposite sides of its plane.
Filtered PairSearch::edge_meets(std::uint32_t p, std::uint32_t q, std::uint32_t face) const {
  const Face& f = faces_[face];
  const Eigen::Vector3d &a = positions_[f[0]], &b = positions_[f[1]], &c = positions_[f[2]];
  const Eigen::Vector3d &from = positions_[p], &to = positions_[q];
  const int side_from = certified_side(planes_[face], a, from);
  const int side_to = certified_side(planes_[face], a, to);
  if (side_from != 0 && side_from == side_to) return Filtered::kNo;
  const int ab = certified_orientation(from, to, a, b);
  const int bc = certified_orientation(from, to, b, c);
  const int ca = certified_orientation(from, to, c, a);
  if (std::min({ab, bc, ca}) < 0 && std::max({ab, bc, ca}) > 0) return Filtered::kNo;
  if (ab != 0 && ab == bc && bc == ca && side_from == -side_to && side_from != 0) {
    return Filtered::kYes;
  }
  return Filtered::kUnknown;
}

/// Whether an edge of one face meets the other: sharing a vertex, only the edge opposite it
/// counts (the others meet the other face at the shared vertex); sharing none, any edge (two
/// closed triangles meet exactly where an edge of one meets the other).
Filtered PairSearch::edges_meet(std::uint32_t t, std::uint32_t u, int shared, int corner_a,
                                int corner_b) const {
  const Face &a = faces_[t], &b = faces_[u];
  bool unknown = false;
  const auto meets = [&](std::uint32_t p, std::uint32_t q, std::uint32_t face) {
    const Filtered meet = edge_meets(p, q, face);
    unknown |= meet == Filtered::kUnknown;
    return meet == Filtered::kYes;
  };
  bool met = false;
  if (shared == 1) {
    met = meets(a[(corner_a + 1) % 3], a[(corner_a + 2) % 3], u) ||
          meets(b[(corner_b + 1) % 3], b[(corner_b + 2) % 3], t);
  } else {
    for (int i = 0; i < 3 && !met; ++i) {
      met = meets(a[i], a[(i + 1) % 3], u) || meets(b[i], b[(i + 1) % 3], t);
    }
  }
  if (met) return Filtered::kYes;
  return unknown ? Filtered::kUnknown : Filtered::kNo;
}

void PairSearch::judge(std::uint32_t t, std::uint32_t u, Tally& tally) const {
  ++tally.candidates;
  std::optional<PairVerdict> verdict;
  if (options_.filter) verdict = filtered(t, u);
  if (!verdict) {
    ++tally.deferred;
    verdict = exact_.judge(t, u);
  }
  switch (*verdict) {
    case PairVerdict::kApart:
      break;
    case PairVerdict::kRepeated:
      ++tally.parts[part_[t]].repeated;
      break;
    case PairVerdict::kMirrored:
      ++tally.parts[part_[t]].mirrored;
      break;
    case PairVerdict::kCrossing:
      ++tally.parts[part_[t]].crossing;
      break;
    case PairVerdict::kMeeting:
      ++tally.meeting[std::minmax(part_[t], part_[u])];
      break;
  }
}

FacePairs PairSearch::total() {
  FacePairs out;
  out.parts.resize(parts_);
  for (const Tally& tally : tallies_) {
    for (std::size_t i = 0; i < parts_; ++i) {
      out.parts[i].repeated += tally.parts[i].repeated;
      out.parts[i].mirrored += tally.parts[i].mirrored;
      out.parts[i].crossing += tally.parts[i].crossing;
    }
    for (const auto& [pair, count] : tally.meeting) out.meeting[pair] += count;
    out.candidates += tally.candidates;
    out.deferred += tally.deferred;
    out.deferred_faces += tally.deferred_faces;
  }
  out.collinear = std::move(collinear_);
  return out;
}

FacePairs PairSearch::run() {
  const std::size_t n = faces_.size();
  planes_.resize(n);
  boxes_.resize(n);
  level_.resize(n);
  in_range_.resize(n);
  collinear_.resize(n);
  choose_cell_size();
  on_threads(threads_, [this](unsigned thread) { prepare(thread); });
  lay_out();
  on_threads(threads_, [this](unsigned thread) { scatter(thread); });
  std::atomic<std::size_t> next{0};
  on_threads(threads_, [&](unsigned thread) {
    for (std::size_t p; (p = next.fetch_add(1)) < kPartitions;) sort_partition(p, tallies_[thread]);
  });
  if (levels_.size() > 1) on_threads(threads_, [this](unsigned thread) { cross_levels(thread); });
  if (!wide_.empty()) on_threads(threads_, [this](unsigned thread) { wide_faces(thread); });
  return total();
}

}  // namespace

FloatBox face_box(const TriangleMesh& mesh, std::uint32_t t) {
  const Face& f = mesh.triangles[t];
  return box_of(mesh.positions[f[0]], mesh.positions[f[1]], mesh.positions[f[2]]);
}

FacePairs find_face_pairs(const TriangleMesh& mesh, const std::vector<std::uint32_t>& triangle_part,
                          std::size_t parts, const ExactFaceTests& exact,
                          const FacePairOptions& options) {
  return PairSearch(mesh, triangle_part, parts, exact, options).run();
}

}  // namespace tumble::engine::detail
