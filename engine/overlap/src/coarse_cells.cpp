// Faces listed by coarse cell (coarse_cells.hpp): a dense counting sort over the cells of the
// mesh's box, on several threads. When that box holds too many cells for the faces (parts
// far apart), or the faces would be listed too often (faces far larger than the cells), the
// cells are not usable and every pair is judged one by one instead.
#include "coarse_cells.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include "certified_orientation.hpp"
#include "face_grid.hpp"

namespace tumble::engine::detail {
namespace {

constexpr double kCoarseCellLimit = 0x1p30;        // cell coordinates are clamped to +-2^30
constexpr std::size_t kListingsPerFace = 4;        // at most this many listings per face on average
constexpr std::size_t kBoxCellsPerFace = 2;        // at most this many cells in the box per face
constexpr std::size_t kMinimumBoxCells = 1 << 16;  // ... or this many
constexpr std::size_t kTooMany = std::numeric_limits<std::size_t>::max() / 2;

/// v / cell rounded down, but for the rounding of the offset: monotone in v. Clamped by
/// min and max rather than std::clamp, whose comparisons compile to branches (v is finite).
std::int32_t coarse_cell_of(double v, double inverse) {
  const double scaled = std::min(std::max(v * inverse, -kCoarseCellLimit), kCoarseCellLimit);
  return static_cast<std::int32_t>(static_cast<std::int64_t>(scaled + kCoarseCellLimit) -
                                   static_cast<std::int64_t>(kCoarseCellLimit));
}

}  // namespace

CoarseCells::CoarseCells(const TriangleMesh& mesh, double cell, unsigned threads)
    : mesh_(mesh), inverse_(1.0 / cell) {
  if (!(inverse_ > 0.0 && std::isfinite(inverse_)) || mesh.triangles.empty()) return;
  threads = std::max(1u, threads);
  find_vertex_cells(threads);
  if (choose_layout()) list_faces(threads);
}

void CoarseCells::find_vertex_cells(unsigned threads) {
  const std::size_t n = mesh_.positions.size();
  vertex_cell_.resize(n);
  in_range_.resize(n);
  std::vector<CellCoordinates> low(threads, CellCoordinates{}), high(threads, CellCoordinates{});
  std::vector<std::uint8_t> all_in_range(threads, 1);
  on_threads(threads, [&](unsigned thread) {
    bool all = true;
    CellCoordinates least{}, most{};
    least.fill(std::numeric_limits<std::int32_t>::max());
    most.fill(std::numeric_limits<std::int32_t>::min());
    const std::size_t first = n * thread / threads, last = n * (thread + 1) / threads;
    for (std::size_t v = first; v < last; ++v) {
      CellCoordinates& c = vertex_cell_[v];
      const Eigen::Vector3d& p = mesh_.positions[v];
      in_range_[v] = detail::in_filter_range(p.x()) && detail::in_filter_range(p.y()) &&
                     detail::in_filter_range(p.z());
      all = all && in_range_[v] != 0;
      for (int axis = 0; axis < 3; ++axis) {
        c[axis] = coarse_cell_of(mesh_.positions[v][axis], inverse_);
        least[axis] = std::min(least[axis], c[axis]);
        most[axis] = std::max(most[axis], c[axis]);
      }
    }
    low[thread] = least;
    high[thread] = most;
    all_in_range[thread] = all ? 1 : 0;
  });
  all_in_range_ = std::find(all_in_range.begin(), all_in_range.end(), 0) == all_in_range.end();
  CellCoordinates least = low.front(), most = high.front();
  for (unsigned thread = 1; thread < threads; ++thread) {
    for (int axis = 0; axis < 3; ++axis) {
      least[axis] = std::min(least[axis], low[thread][axis]);
      most[axis] = std::max(most[axis], high[thread][axis]);
    }
  }
  origin_ = least;
  for (int axis = 0; axis < 3; ++axis) {
    extent_[axis] = std::int64_t{most[axis]} - least[axis] + 1;
  }
}

/// Whether the dense array of the box's cells is small enough.
bool CoarseCells::choose_layout() {
  const std::size_t limit = std::max(kMinimumBoxCells, kBoxCellsPerFace * mesh_.triangles.size());
  double cells = 1.0;
  for (int axis = 0; axis < 3; ++axis) cells *= static_cast<double>(extent_[axis]);
  return cells <= static_cast<double>(limit);
}

inline CoarseCells::Range CoarseCells::range(std::uint32_t t) const {
  const auto& f = mesh_.triangles[t];
  const CellCoordinates &a = vertex_cell_[f[0]], &b = vertex_cell_[f[1]], &c = vertex_cell_[f[2]];
  Range r;
  for (int axis = 0; axis < 3; ++axis) {
    r.low[axis] = std::min({a[axis], b[axis], c[axis]});
    r.high[axis] = std::max({a[axis], b[axis], c[axis]});
  }
  return r;
}

std::size_t CoarseCells::dense_index(const CellCoordinates& c) const {
  return static_cast<std::size_t>(
      ((std::int64_t{c[2]} - origin_[2]) * extent_[1] + (std::int64_t{c[1]} - origin_[1])) *
          extent_[0] +
      (std::int64_t{c[0]} - origin_[0]));
}

/// Where face t is listed (spans beyond 0xffff clamped to it). Inline: called out of line, its
/// 10-byte result went through the stack in pieces and was read back whole, a stalled load per
/// face: listing the 1M-triangle torus's faces took 25 ms on one thread or two, and takes 14.5
/// and 11.5 ms inlined (BM_OverlapCheckTorusTwoThreads 41.6 -> 31.1 ms).
inline CoarseCells::Listing CoarseCells::listing(std::uint32_t t) const {
  const auto& f = mesh_.triangles[t];
  const std::uint32_t first = vertex_index_[f[0]];
  if (first == vertex_index_[f[1]] && first == vertex_index_[f[2]]) return {first, {0, 0, 0}};
  const Range r = range(t);
  Listing out{static_cast<std::uint32_t>(dense_index(r.low)), {0, 0, 0}};
  for (int axis = 0; axis < 3; ++axis) {
    const std::int64_t span = std::int64_t{r.high[axis]} - r.low[axis];
    out.span[axis] = static_cast<std::uint16_t>(std::min<std::int64_t>(span, 0xffff));
  }
  return out;
}

/// The directions along which face t projects with certainly positive orientation (see
/// directions()): along axis a, the orientation of its corners in the plane of the next two
/// axes; seen from the other side the plane's axes swap and the sign flips exactly (the same
/// products, subtracted the other way), so one sign serves both directions.
inline std::uint8_t CoarseCells::face_directions(std::uint32_t t) const {
  const auto& f = mesh_.triangles[t];
  if (!all_in_range_ && (in_range_[f[0]] & in_range_[f[1]] & in_range_[f[2]]) == 0) return 0;
  const Eigen::Vector3d &a = mesh_.positions[f[0]], &b = mesh_.positions[f[1]],
                        &c = mesh_.positions[f[2]];
  unsigned out = 0;
  for (int axis = 0; axis < 3; ++axis) {
    const int u = axis == 2 ? 0 : axis + 1, v = axis == 0 ? 2 : axis - 1;
    const int sign = certified_orientation_2d(b[u], b[v], c[u], c[v], a[u], a[v]);
    out |= (sign > 0 ? 1u : 0u) << (2 * axis);
    out |= (sign < 0 ? 1u : 0u) << (2 * axis + 1);
  }
  return static_cast<std::uint8_t>(out);
}

/// Counts each cell's faces per thread and notes, per cell, the directions every face listed
/// there allows (face_directions, ANDed), numbers the cells where faces are listed, then lists
/// the faces that span several cells. Each vertex's cell is first given by its index in the box:
/// a face whose three agree (most faces, the cells being many times larger than they) lies in
/// that cell alone. The count notes that cell per face (face_cell_), so telling later that a
/// face lies in one cell reads one number, not the face's three vertices.
void CoarseCells::list_faces(unsigned threads) {
  const std::size_t cells = static_cast<std::size_t>(extent_[0] * extent_[1] * extent_[2]);
  const std::size_t n = mesh_.triangles.size(), vertices = mesh_.positions.size();
  const auto stride_y = static_cast<std::size_t>(extent_[0]);
  const auto stride_z = static_cast<std::size_t>(extent_[0] * extent_[1]);
  // Calls visit(cell) for every cell in the box of a listing.
  const auto for_each_cell = [&](const Listing& listing, const auto& visit) {
    for (std::size_t z = 0; z <= listing.span[2]; ++z) {
      for (std::size_t y = 0; y <= listing.span[1]; ++y) {
        const std::size_t row = listing.low + z * stride_z + y * stride_y;
        for (std::size_t x = 0; x <= listing.span[0]; ++x) visit(row + x);
      }
    }
  };
  vertex_index_.resize(vertices);
  // Each slice's ends are locals: in the loops' tests (the vectors written through captured
  // references may alias them, for all the compiler knows) a division ran at every face.
  on_threads(threads, [&](unsigned thread) {
    const std::size_t first = vertices * thread / threads;
    const std::size_t last = vertices * (thread + 1) / threads;
    for (std::size_t v = first; v < last; ++v) {
      vertex_index_[v] = static_cast<std::uint32_t>(dense_index(vertex_cell_[v]));
    }
  });
  // Per thread and cell: the spanning faces listed there, and the directions its faces allow
  // (all six until a face is listed: a face allows at most one of the two along each axis).
  std::vector<std::vector<std::uint32_t>> count(threads, std::vector<std::uint32_t>(cells, 0));
  std::vector<std::vector<std::uint8_t>> directions(
      threads, std::vector<std::uint8_t>(cells, kAllDirections));
  std::vector<std::size_t> listings(threads, 0), spanning(threads, 0);
  face_cell_.resize(n);
  on_threads(threads, [&](unsigned thread) {
    std::vector<std::uint32_t>& mine = count[thread];
    std::vector<std::uint8_t>& allowed = directions[thread];
    std::size_t total = 0, spanning_total = 0;
    const std::size_t first = n * thread / threads, last = n * (thread + 1) / threads;
    for (std::size_t t = first; t < last; ++t) {
      const auto face = static_cast<std::uint32_t>(t);
      const Listing l = listing(face);
      const std::uint8_t along = face_directions(face);
      const bool alone = (l.span[0] | l.span[1] | l.span[2]) == 0;
      face_cell_[t] = alone ? l.low : kSpanning;
      if (alone) {
        allowed[l.low] &= along;
        ++total;
        continue;
      }
      if (std::max({l.span[0], l.span[1], l.span[2]}) == 0xffff) total = kTooMany;
      if (total > kListingsPerFace * n) break;
      for_each_cell(l, [&](std::size_t cell) {
        ++mine[cell];
        allowed[cell] &= along;
        ++total;
        ++spanning_total;
      });
    }
    listings[thread] = total;
    spanning[thread] = spanning_total;
  });
  std::size_t total = 0, spanning_total = 0;
  for (unsigned thread = 0; thread < threads; ++thread) {
    total = std::min(kTooMany, total + listings[thread]);
    spanning_total += spanning[thread];
  }
  if (total > kListingsPerFace * n) return;
  number_cells(count, directions);
  faces_.resize(spanning_total);
  on_threads(threads, [&](unsigned thread) {
    std::vector<std::uint32_t>& cursor = count[thread];
    const std::size_t first = n * thread / threads, last = n * (thread + 1) / threads;
    for (std::size_t t = first; t < last; ++t) {
      if (face_cell_[t] != kSpanning) continue;
      const auto face = static_cast<std::uint32_t>(t);
      for_each_cell(listing(face), [&](std::size_t cell) { faces_[cursor[cell]++] = face; });
    }
  });
  usable_ = true;
}

/// Numbers the cells where faces are listed (some thread's directions narrowed there), ANDs
/// their directions, and turns each thread's counts of spanning faces into its cursors.
void CoarseCells::number_cells(std::vector<std::vector<std::uint32_t>>& count,
                               const std::vector<std::vector<std::uint8_t>>& directions) {
  const std::size_t cells = count.front().size();
  index_.assign(cells, 0);
  start_.push_back(0);
  for (std::size_t cell = 0; cell < cells; ++cell) {
    std::uint32_t offset = start_.back();
    std::uint8_t allowed = kAllDirections;
    bool listed = false;
    for (std::size_t thread = 0; thread < count.size(); ++thread) {
      const std::uint32_t here = count[thread][cell];
      count[thread][cell] = offset;  // now the thread's cursor in this cell
      offset += here;
      allowed &= directions[thread][cell];
      listed = listed || directions[thread][cell] != kAllDirections;
    }
    if (!listed) continue;
    index_[cell] = static_cast<std::uint32_t>(coordinates_.size() + 1);
    const auto c = static_cast<std::int64_t>(cell);
    coordinates_.push_back({static_cast<std::int32_t>(origin_[0] + c % extent_[0]),
                            static_cast<std::int32_t>(origin_[1] + c / extent_[0] % extent_[1]),
                            static_cast<std::int32_t>(origin_[2] + c / extent_[0] / extent_[1])});
    directions_.push_back(allowed);
    start_.push_back(offset);
  }
}

CellCoordinates CoarseCells::pair_cell(std::uint32_t t, std::uint32_t u) const {
  const Range a = range(t), b = range(u);
  return {std::max(a.low[0], b.low[0]), std::max(a.low[1], b.low[1]), std::max(a.low[2], b.low[2])};
}

std::optional<std::size_t> CoarseCells::find(const CellCoordinates& c) const {
  for (int axis = 0; axis < 3; ++axis) {
    const std::int64_t offset = std::int64_t{c[axis]} - origin_[axis];
    if (offset < 0 || offset >= extent_[axis]) return std::nullopt;
  }
  const std::uint32_t index = index_[dense_index(c)];
  if (index == 0) return std::nullopt;
  return index - 1;
}

}  // namespace tumble::engine::detail
