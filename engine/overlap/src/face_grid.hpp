#pragma once
// A hashed uniform grid over the boxes of a mesh's faces, with coarser levels for larger faces
// (face_grid.cpp): the candidate pairs of the overlap checks (face_pairs.cpp).
//
// Level l has cells of size 2^l c. A face goes to the first level on which its box spans at
// most two cells along each axis, and into every cell its box touches there (at most eight).
// Two faces of one level whose boxes overlap share the cell holding the low corner of their
// boxes' intersection, and belong to it alone: in each cell an entry knows along which axes
// the cell is one past its face's lowest cell (its corner bits), and a pair belongs to the
// cell exactly when no axis has the bit set for both (owns_pair). Faces of different levels
// are paired by looking the finer one up on the coarser level (for_each_in).

#include <array>
#include <compare>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <memory>
#include <span>
#include <thread>
#include <utility>
#include <vector>

#include "face_pairs.hpp"

namespace tumble::engine::detail {

struct GridCell {
  std::int32_t level, x, y, z;
  auto operator<=>(const GridCell&) const = default;
};

/// The cells a box touches on one level: [low, high] along each axis.
struct CellRange {
  std::array<std::int32_t, 3> low, high;
};

/// A face in one of its cells.
struct GridItem {
  GridCell cell;
  FloatBox box;
  std::uint32_t face;
  std::uint32_t corner;  ///< bit a: the cell is one past the face's lowest cell along axis a
};

/// Whether a pair of faces of one cell belongs to it (see above).
inline bool owns_pair(const GridItem& a, const GridItem& b) {
  return (a.corner & b.corner) == 0;
}

inline bool boxes_overlap(const FloatBox& a, const FloatBox& b) {
  return a.lo[0] <= b.hi[0] && b.lo[0] <= a.hi[0] && a.lo[1] <= b.hi[1] && b.lo[1] <= a.hi[1] &&
         a.lo[2] <= b.hi[2] && b.lo[2] <= a.hi[2];
}

/// What is done with the faces of each cell; called on several threads at once.
class CellVisitor {
 public:
  virtual ~CellVisitor() = default;
  /// `items`: the faces of one cell (at least one), in no particular order.
  virtual void visit(unsigned thread, std::span<const GridItem> items) = 0;
};

/// Runs work(thread) on `threads` threads (this one is thread 0), rethrowing the first error.
template <typename Work>
void on_threads(unsigned threads, const Work& work);

class FaceGrid {
 public:
  /// Places the faces t with include[t] != 0, level 0 cells 1 / inverse_cell wide, at most
  /// `levels` levels; a face spanning more than two cells along an axis on all of them is left
  /// out (oversized()). Builds on `threads` threads.
  FaceGrid(const std::vector<FloatBox>& boxes, const std::vector<std::uint8_t>& include,
           double inverse_cell, int levels, unsigned threads);

  /// Calls the visitor once for every non-empty cell, on the grid's threads.
  void visit(CellVisitor& visitor);

  const std::vector<std::uint32_t>& oversized() const { return oversized_; }
  /// The levels holding faces, ascending.
  const std::vector<std::int32_t>& levels() const { return levels_; }
  /// A placed face's level.
  std::int32_t level(std::uint32_t face) const { return level_[face]; }
  bool placed(std::uint32_t face) const { return level_[face] < kOutside; }
  double inverse(std::int32_t level) const { return inverses_[static_cast<std::size_t>(level)]; }
  CellRange cells(const FloatBox& box, std::int32_t level) const;
  /// Calls visit(face, corner) for every face placed in `cell` (on its level); after visit().
  template <typename Visit>
  void for_each_in(const GridCell& cell, const Visit& visit) const;
  unsigned threads() const { return threads_; }

  static constexpr int kMaxLevels = 250;

 private:
  struct Entry {
    std::uint32_t hash;         ///< of the cell
    std::uint32_t face_corner;  ///< face | corner << kCornerShift
  };
  struct Scratch;
  static constexpr int kPartitionBits = 8;
  static constexpr std::size_t kPartitions = std::size_t{1} << kPartitionBits;
  static constexpr int kCornerShift = 29;
  static constexpr std::uint32_t kFaceMask = (std::uint32_t{1} << kCornerShift) - 1;
  static constexpr std::uint8_t kOutside = 254;

  std::pair<std::size_t, std::size_t> slice(unsigned thread) const;
  void place(unsigned thread, std::array<std::size_t, kPartitions>& counts,
             std::vector<std::uint32_t>& oversized, std::vector<bool>& levels);
  void lay_out(const std::vector<std::array<std::size_t, kPartitions>>& counts);
  void scatter(unsigned thread, std::array<std::size_t, kPartitions>& cursor);
  void sort_partition(std::size_t partition, unsigned thread, Scratch& scratch,
                      CellVisitor& visitor);
  GridCell cell_of(const Entry& entry) const;
  std::pair<const Entry*, const Entry*> bucket(const GridCell& cell) const;

  const std::vector<FloatBox>& boxes_;
  const std::vector<std::uint8_t>& include_;
  const unsigned threads_;
  const int max_levels_;
  std::vector<double> inverses_;
  std::vector<std::uint8_t> level_;
  std::vector<std::int32_t> levels_;
  std::vector<std::uint32_t> oversized_;
  std::unique_ptr<Entry[]> entries_;
  std::array<std::size_t, kPartitions + 1> partition_start_{};
  std::array<std::size_t, kPartitions + 1> first_bucket_{};
  std::vector<std::uint32_t> bucket_start_;  ///< per partition: its buckets' starts, then its end
  std::vector<std::array<std::size_t, kPartitions>> cursors_;
};

// ---- implementation of the templates

/// A 32-bit hash of a cell (multiply-xorshift rounds).
std::uint32_t grid_cell_hash(std::int32_t level, std::int32_t x, std::int32_t y, std::int32_t z);

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

template <typename Visit>
void FaceGrid::for_each_in(const GridCell& cell, const Visit& visit) const {
  const auto [begin, end] = bucket(cell);
  for (const Entry* entry = begin; entry != end; ++entry) {
    const std::uint32_t face = entry->face_corner & kFaceMask;
    if (level_[face] != cell.level || !(cell_of(*entry) == cell)) continue;
    visit(face, entry->face_corner >> kCornerShift);
  }
}

}  // namespace tumble::engine::detail
