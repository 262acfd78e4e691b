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

constexpr std::size_t kListingsPerFace = 4;        // at most this many listings per face on average
constexpr std::size_t kBoxCellsPerFace = 2;        // at most this many cells in the box per face
constexpr std::size_t kMinimumBoxCells = 1 << 16;  // ... or this many
constexpr std::size_t kTooMany = std::numeric_limits<std::size_t>::max() / 2;

}  // namespace

CoarseCells::CoarseCells(const TriangleMesh& mesh, double cell, unsigned threads,
                         const std::optional<Bounds>& bounds)
    : mesh_(mesh), inverse_(1.0 / cell) {
  if (!(inverse_ > 0.0 && std::isfinite(inverse_)) || mesh.triangles.empty() ||
      mesh.triangles.size() >= (std::size_t{1} << kFaceBits)) {
    return;  // not usable: a listing keeps its face in kFaceBits bits
  }
  threads = std::max(1u, threads);
  // Given the bounds, the pass that numbers the vertices' cells also tells whether they are in
  // the filter's range; a vertex outside the given box sends it back to find the box itself.
  if (bounds) {
    set_box(*bounds);
  } else {
    find_box(threads);
  }
  if (!choose_layout()) return;
  if (!find_vertex_cells(threads)) {
    find_box(threads);  // only with a given box (the box found holds every vertex)
    if (!choose_layout() || !find_vertex_cells(threads)) return;
  }
  list_faces(threads);
}

/// The box of the cells from the least and the greatest coordinates (cell_of is monotone).
void CoarseCells::set_box(const Bounds& bounds) {
  for (int axis = 0; axis < 3; ++axis) {
    origin_[axis] = cell_of(bounds.first[axis]);
    extent_[axis] = std::int64_t{cell_of(bounds.second[axis])} - origin_[axis] + 1;
  }
}

/// The box of the vertices' cells, from their least and greatest coordinates.
void CoarseCells::find_box(unsigned threads) {
  const std::vector<Eigen::Vector3d>& positions = mesh_.positions;
  const std::size_t n = positions.size();
  std::vector<Bounds> box(threads, {positions.front(), positions.front()});
  on_threads(threads, [&](unsigned thread) {
    Bounds mine = box[thread];
    const std::size_t first = n * thread / threads, last = n * (thread + 1) / threads;
    for (std::size_t v = first; v < last; ++v) {
      mine.first = mine.first.cwiseMin(positions[v]);
      mine.second = mine.second.cwiseMax(positions[v]);
    }
    box[thread] = mine;
  });
  Bounds all = box.front();
  for (const Bounds& part : box) {
    all.first = all.first.cwiseMin(part.first);
    all.second = all.second.cwiseMax(part.second);
  }
  set_box(all);
}

/// Which vertices are in the filter's range, when some is not.
void CoarseCells::find_in_range() {
  const std::vector<Eigen::Vector3d>& positions = mesh_.positions;
  in_range_.resize(positions.size());
  for (std::size_t v = 0; v < positions.size(); ++v) {
    const Eigen::Vector3d& p = positions[v];
    in_range_[v] = in_filter_range(p.x()) && in_filter_range(p.y()) && in_filter_range(p.z());
  }
}

/// Whether the dense array of the box's cells is small enough.
bool CoarseCells::choose_layout() {
  const std::size_t limit = std::max(kMinimumBoxCells, kBoxCellsPerFace * mesh_.triangles.size());
  double cells = 1.0;
  for (int axis = 0; axis < 3; ++axis) cells *= static_cast<double>(extent_[axis]);
  return cells <= static_cast<double>(limit);
}

/// Each vertex's cell, as its index in the box, and whether every vertex is in the filter's
/// range. False when a vertex lies outside the box.
bool CoarseCells::find_vertex_cells(unsigned threads) {
  const std::size_t vertices = mesh_.positions.size();
  vertex_index_.resize(vertices);
  std::vector<std::uint8_t> all_in_range(threads, 1), inside(threads, 1);
  // Each slice's ends are locals: in the loops' tests (the vectors written through captured
  // references may alias them, for all the compiler knows) a division ran at every element.
  on_threads(threads, [&](unsigned thread) {
    const std::size_t first = vertices * thread / threads;
    const std::size_t last = vertices * (thread + 1) / threads;
    bool all = true, in_box = true;
    for (std::size_t v = first; v < last; ++v) {
      const Eigen::Vector3d& p = mesh_.positions[v];
      const CellCoordinates c = vertex_cell(static_cast<std::uint32_t>(v));
      for (int axis = 0; axis < 3; ++axis) {
        const std::int64_t offset = std::int64_t{c[axis]} - origin_[axis];
        in_box &= (offset >= 0) & (offset < extent_[axis]);
      }
      all = all && in_filter_range(p.x()) && in_filter_range(p.y()) && in_filter_range(p.z());
      vertex_index_[v] = static_cast<std::uint32_t>(dense_index(c));
    }
    all_in_range[thread] = all ? 1 : 0;
    inside[thread] = in_box ? 1 : 0;
  });
  if (std::find(inside.begin(), inside.end(), 0) != inside.end()) return false;
  all_in_range_ = std::find(all_in_range.begin(), all_in_range.end(), 0) == all_in_range.end();
  if (!all_in_range_) find_in_range();
  return true;
}

inline CoarseCells::Range CoarseCells::range(const CellCoordinates (&corner)[3]) {
  Range r;
  for (int axis = 0; axis < 3; ++axis) {
    r.low[axis] = std::min({corner[0][axis], corner[1][axis], corner[2][axis]});
    r.high[axis] = std::max({corner[0][axis], corner[1][axis], corner[2][axis]});
  }
  return r;
}

/// Where a face whose corners' cells span `r` is listed (spans beyond 0xffff clamped to it).
/// Inline: called out of line, its 10-byte result went through the stack in pieces and was read
/// back whole, a stalled load per face (listing the 1M-triangle torus's faces took 25 ms, then
/// 14.5 ms inlined).
inline CoarseCells::Listing CoarseCells::listing(const Range& r) const {
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
    out |= static_cast<unsigned>(sign > 0) << (2 * axis);
    out |= static_cast<unsigned>(sign < 0) << (2 * axis + 1);
  }
  return static_cast<std::uint8_t>(out);
}

/// The edges of a face with corners in cells `corner` that lie outside cell `cell`: both ends
/// below it, or both above it, along some axis (bit k: the edge from corner k to corner k + 1).
inline std::uint32_t CoarseCells::edges_outside(const CellCoordinates (&corner)[3],
                                                const CellCoordinates& cell) {
  unsigned below[3] = {0, 0, 0}, above[3] = {0, 0, 0};
  for (int k = 0; k < 3; ++k) {
    for (int axis = 0; axis < 3; ++axis) {
      below[k] |= (corner[k][axis] < cell[axis] ? 1u : 0u) << axis;
      above[k] |= (corner[k][axis] > cell[axis] ? 1u : 0u) << axis;
    }
  }
  std::uint32_t out = 0;
  for (int k = 0; k < 3; ++k) {
    const int next = k == 2 ? 0 : k + 1;
    if ((below[k] & below[next]) != 0 || (above[k] & above[next]) != 0) out |= 1u << k;
  }
  return out;
}

/// The coordinates of the cell with index `cell` in the box.
CellCoordinates CoarseCells::cell_at(std::size_t cell) const {
  const auto c = static_cast<std::int64_t>(cell);
  return {static_cast<std::int32_t>(origin_[0] + c % extent_[0]),
          static_cast<std::int32_t>(origin_[1] + c / extent_[0] % extent_[1]),
          static_cast<std::int32_t>(origin_[2] + c / extent_[0] / extent_[1])};
}

/// Counts each cell's faces per thread and notes, per cell, the directions every face listed
/// there allows (face_directions, ANDed), numbers the cells where faces are listed, then lists
/// the faces that span several cells, which the count noted. A face whose three vertices have
/// one cell (most faces, the cells being many times larger than they) lies in that cell alone.
void CoarseCells::list_faces(unsigned threads) {
  const std::size_t cells = static_cast<std::size_t>(extent_[0] * extent_[1] * extent_[2]);
  const std::size_t n = mesh_.triangles.size();
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
  // Per thread and cell: the spanning faces listed there, and the directions its faces allow
  // (all six until a face is listed: a face allows at most one of the two along each axis).
  std::vector<std::vector<std::uint32_t>> count(threads, std::vector<std::uint32_t>(cells, 0));
  std::vector<std::vector<std::uint8_t>> directions(
      threads, std::vector<std::uint8_t>(cells, kAllDirections));
  // Per thread, the faces spanning several cells, in order, with their corners' cells (read
  // back in order by the listing below, instead of the faces' corners again at random).
  std::vector<std::vector<SpanningFace>> spanning(threads);
  std::vector<std::size_t> listings(threads, 0);
  on_threads(threads, [&](unsigned thread) {
    std::vector<std::uint32_t>& mine = count[thread];
    std::vector<std::uint8_t>& allowed = directions[thread];
    std::vector<SpanningFace>& spanning_faces = spanning[thread];
    std::size_t total = 0;
    const std::size_t first = n * thread / threads, last = n * (thread + 1) / threads;
    // Room for a sixteenth of the faces (about as many as span cells on the 1M-triangle torus).
    spanning_faces.reserve((last - first) / 16);
    for (std::size_t t = first; t < last; ++t) {
      const auto face = static_cast<std::uint32_t>(t);
      const auto& f = mesh_.triangles[t];
      const std::uint8_t along = face_directions(face);
      const std::uint32_t cell = vertex_index_[f[0]];
      if (cell == vertex_index_[f[1]] && cell == vertex_index_[f[2]]) {
        allowed[cell] &= along;
        ++total;
        continue;
      }
      const SpanningFace spanning_face{face,
                                       {vertex_cell(f[0]), vertex_cell(f[1]), vertex_cell(f[2])}};
      const Listing l = listing(range(spanning_face.corner));
      if (std::max({l.span[0], l.span[1], l.span[2]}) == 0xffff) total = kTooMany;
      if (total > kListingsPerFace * n) break;
      spanning_faces.push_back(spanning_face);
      for_each_cell(l, [&](std::size_t listed) {
        ++mine[listed];
        allowed[listed] &= along;
        ++total;
      });
    }
    listings[thread] = total;
  });
  std::size_t total = 0;
  for (const std::size_t listed : listings) total = std::min(kTooMany, total + listed);
  if (total > kListingsPerFace * n) return;
  number_cells(count, directions);
  list_spanning(threads, count, spanning);
  usable_ = true;
}

/// Lists each face spanning several cells in every cell it spans, at the threads' cursors,
/// with the edges of it that lie outside each cell.
void CoarseCells::list_spanning(unsigned threads, std::vector<std::vector<std::uint32_t>>& count,
                                const std::vector<std::vector<SpanningFace>>& spanning) {
  const auto stride_y = static_cast<std::size_t>(extent_[0]);
  const auto stride_z = static_cast<std::size_t>(extent_[0] * extent_[1]);
  faces_.resize(start_.back());
  on_threads(threads, [&](unsigned thread) {
    std::vector<std::uint32_t>& cursor = count[thread];
    for (const SpanningFace& spanning_face : spanning[thread]) {
      const CellCoordinates(&corner)[3] = spanning_face.corner;
      const Range r = range(corner);
      const Listing l = listing(r);
      // The listing's lowest cell, and each cell's coordinates stepped from it.
      const CellCoordinates& low = r.low;
      for (std::int32_t z = 0; z <= l.span[2]; ++z) {
        for (std::int32_t y = 0; y <= l.span[1]; ++y) {
          const std::size_t row = l.low + static_cast<std::size_t>(z) * stride_z +
                                  static_cast<std::size_t>(y) * stride_y;
          for (std::int32_t x = 0; x <= l.span[0]; ++x) {
            const CellCoordinates cell{low[0] + x, low[1] + y, low[2] + z};
            faces_[cursor[row + static_cast<std::size_t>(x)]++] =
                spanning_face.face | edges_outside(corner, cell) << kFaceBits;
          }
        }
      }
    }
  });
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
    coordinates_.push_back(cell_at(cell));
    directions_.push_back(allowed);
    start_.push_back(offset);
  }
}

/// The least coordinates' cell: cell_of is monotone, so that is the least of the corners'
/// cells, at a third of the cost.
CellCoordinates CoarseCells::low_cell(std::uint32_t t) const {
  const auto& f = mesh_.triangles[t];
  const Eigen::Vector3d low =
      mesh_.positions[f[0]].cwiseMin(mesh_.positions[f[1]]).cwiseMin(mesh_.positions[f[2]]);
  return {cell_of(low.x()), cell_of(low.y()), cell_of(low.z())};
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
