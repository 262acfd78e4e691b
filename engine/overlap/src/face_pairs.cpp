// Face pairs: coarse regions certified whole, the other pairs from a fine grid, judged by a
// certified filter (face_pairs.hpp).
//
// Design. Each pair of faces whose boxes overlap belongs to one coarse cell: the one holding
// the low corner of the boxes' intersection (face_grid.hpp; both faces touch that cell). A
// coarse cell whose faces are certified apart (region_certificate.hpp) settles all its pairs
// at once; on a smooth mesh that is every cell, at a cost linear in the faces. The faces
// touching a cell that is not certified are placed in the fine grid (cells twice the faces'
// median extent), and each of their pairs is judged if it belongs to such a cell. Counts are
// summed per thread and added up at the end, so the result does not depend on the threads.
#include "face_pairs.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "certified_orientation.hpp"
#include "coarse_cells.hpp"
#include "face_grid.hpp"
#include "region_certificate.hpp"

namespace tumble::engine::detail {
namespace {

using Face = std::array<std::uint32_t, 3>;

constexpr double kFineCellsPerExtent = 2.0;  // fine cell size over the median face extent
// Coarse cell size over it. Larger cells put fewer faces in two cells and give shorter
// outlines a face, until curvature makes the projection fail: on the 1M-triangle torus 32
// checks in 0.81x the time of 16 (0.85x on two threads); 48 fails there; the hollow balls
// (no cell certified) and assimp's test models take the same time at 16 and 32.
constexpr double kCoarseCellsPerExtent = 32.0;

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

FloatBox box_of(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  FloatBox box;
  for (int axis = 0; axis < 3; ++axis) {
    box.lo[axis] = float_down(std::min({a[axis], b[axis], c[axis]}));
    box.hi[axis] = float_up(std::max({a[axis], b[axis], c[axis]}));
  }
  return box;
}

/// What the filter can tell: certainly not, certainly, or not at all.
enum class Filtered { kNo, kYes, kUnknown };

/// One thread's counts and scratch memory.
struct Tally {
  std::vector<PartPairCounts> parts;
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> meeting;
  std::size_t candidates = 0, deferred = 0, deferred_faces = 0, regions = 0, certified = 0;
};

class PairSearch {
 public:
  PairSearch(const TriangleMesh& mesh, const std::vector<std::uint32_t>& triangle_part,
             std::size_t parts, const ExactFaceTests& exact, const FacePairOptions& options);
  FacePairs run();

 private:
  friend class PairVisitor;

  std::pair<std::size_t, std::size_t> slice(unsigned thread) const {
    const std::size_t n = faces_.size();
    return {n * thread / threads_, n * (thread + 1) / threads_};
  }
  void prepare(unsigned thread);
  double median_extent() const;
  void certify_regions(double cell);
  void find_pairs(double cell);
  void cross_levels(const FaceGrid& grid, unsigned thread);
  bool belongs_to_uncertified(std::uint32_t t, std::uint32_t u) const;
  void judge(std::uint32_t t, std::uint32_t u, Tally& tally) const;
  std::optional<PairVerdict> filtered(std::uint32_t t, std::uint32_t u) const;
  Filtered straddle(const Face& a, unsigned skip, std::uint32_t plane_face) const;
  Filtered edge_meets(std::uint32_t p, std::uint32_t q, std::uint32_t face) const;
  Filtered edges_meet(std::uint32_t t, std::uint32_t u, int shared, int corner_a,
                      int corner_b) const;
  bool one_side(std::uint32_t corners_face, std::uint32_t plane_face) const;
  FacePairs total();

  const TriangleMesh& mesh_;
  const std::vector<Eigen::Vector3d>& positions_;
  const std::vector<Face>& faces_;
  const std::vector<std::uint32_t>& part_;
  const std::size_t parts_;
  const ExactFaceTests& exact_;
  const FacePairOptions options_;
  const unsigned threads_;
  std::vector<FloatBox> boxes_;
  std::vector<FacePlane> planes_;
  std::vector<std::uint8_t> in_range_;  ///< 1 when the filter may judge the face
  std::vector<std::uint8_t> collinear_;
  std::vector<std::uint8_t> active_;  ///< 1: judged in the fine grid
  std::vector<Tally> tallies_;
  std::optional<CoarseCells> coarse_;
  bool certifying_ = false;
  bool any_active_ = true;                 ///< whether any face is left for the fine grid
  std::vector<std::uint8_t> uncertified_;  ///< per coarse cell
  /// Per face judged in the fine grid, when regions were certified: its lowest coarse cell
  /// (found once a face, not at each of its pairs).
  std::vector<CellCoordinates> low_cell_;
};

PairSearch::PairSearch(const TriangleMesh& mesh, const std::vector<std::uint32_t>& triangle_part,
                       std::size_t parts, const ExactFaceTests& exact,
                       const FacePairOptions& options)
    : mesh_(mesh),
      positions_(mesh.positions),
      faces_(mesh.triangles),
      part_(triangle_part),
      parts_(parts),
      exact_(exact),
      options_(options),
      // Small meshes on one thread: starting threads would cost more than it saves.
      threads_(static_cast<unsigned>(std::clamp<std::size_t>(mesh.triangles.size() / 8192, 1,
                                                             std::max(1u, options.threads)))) {
  tallies_.resize(threads_);
  for (Tally& tally : tallies_) tally.parts.resize(parts_);
}

/// An active face's box, plane and collinearity, and whether the filter may judge it (the
/// faces of certified regions are not collinear: they project with non-zero area).
void PairSearch::prepare(unsigned thread) {
  const auto [first, last] = slice(thread);
  Tally& tally = tallies_[thread];
  for (std::size_t t = first; t < last; ++t) {
    if (active_[t] == 0) continue;
    const Face& f = faces_[t];
    const Eigen::Vector3d &o = positions_[f[0]], &a = positions_[f[1]], &b = positions_[f[2]];
    bool in_range = true;
    for (const Eigen::Vector3d* p : {&o, &a, &b}) {
      in_range &= in_filter_range(p->x()) && in_filter_range(p->y()) && in_filter_range(p->z());
    }
    in_range_[t] = in_range ? 1 : 0;
    bool not_collinear = false;
    planes_[t] = face_plane(o, a, b, not_collinear);
    if (!(options_.filter && in_range && not_collinear)) {
      ++tally.deferred_faces;
      not_collinear = !exact_.collinear(static_cast<std::uint32_t>(t));
    }
    collinear_[t] = not_collinear ? 0 : 1;
    boxes_[t] = box_of(o, a, b);
    if (certifying_) low_cell_[t] = coarse_->low_cell(static_cast<std::uint32_t>(t));
  }
}

/// The median extent of up to 1024 faces spread over the mesh (1 when there are none).
double PairSearch::median_extent() const {
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
  if (extents.empty()) return 1.0;
  const auto middle = extents.begin() + static_cast<std::ptrdiff_t>(extents.size() / 2);
  std::nth_element(extents.begin(), middle, extents.end());
  return *middle;
}

/// Certifies each coarse cell's faces; marks the faces of the others for the fine grid.
void PairSearch::certify_regions(double cell) {
  coarse_.emplace(mesh_, cell, threads_, options_.bounds);
  if (!coarse_->usable()) return;
  uncertified_.assign(coarse_->size(), 0);
  std::atomic<std::size_t> next{0};
  std::atomic<bool> any_uncertified{false};
  on_threads(threads_, [&](unsigned thread) {
    RegionCertificate certificate(mesh_);
    Tally& tally = tallies_[thread];
    for (std::size_t i; (i = next.fetch_add(1, std::memory_order_relaxed)) < coarse_->size();) {
      ++tally.regions;
      if (certificate.certify(coarse_->faces(i), coarse_->directions(i))) {
        ++tally.certified;
        continue;
      }
      uncertified_[i] = 1;
      any_uncertified.store(true, std::memory_order_relaxed);
      for (const std::uint32_t entry : coarse_->faces(i)) {
        const std::uint32_t f = entry & ((1u << CoarseCells::kFaceBits) - 1);
        std::atomic_ref<std::uint8_t>(active_[f]).store(1, std::memory_order_relaxed);
      }
    }
  });
  certifying_ = true;
  any_active_ = any_uncertified.load();
  if (!any_active_) return;
  // The faces lying in one cell that is not certified (those spanning cells are marked above).
  on_threads(threads_, [&](unsigned thread) {
    const auto [first, last] = slice(thread);
    for (std::size_t t = first; t < last; ++t) {
      const auto face = static_cast<std::uint32_t>(t);
      if (coarse_->in_one_cell(face) && uncertified_[coarse_->cell_of_face(face)] != 0) {
        active_[t] = 1;
      }
    }
  });
}

/// Whether a pair of faces whose boxes overlap belongs to a coarse cell that is not certified.
bool PairSearch::belongs_to_uncertified(std::uint32_t t, std::uint32_t u) const {
  if (!certifying_) return true;
  const std::optional<std::size_t> cell =
      coarse_->find(CoarseCells::pair_cell(low_cell_[t], low_cell_[u]));
  return !cell || uncertified_[*cell] != 0;
}

/// Judges the pairs of faces of one fine cell that belong to it.
class PairVisitor final : public CellVisitor {
 public:
  explicit PairVisitor(const PairSearch& search) : search_(search) {}
  void visit(unsigned thread, std::span<const GridItem> items) override {
    Tally& tally = const_cast<Tally&>(search_.tallies_[thread]);
    for (std::size_t i = 0; i < items.size(); ++i) {
      for (std::size_t j = i + 1; j < items.size(); ++j) {
        if (!owns_pair(items[i], items[j]) || !boxes_overlap(items[i].box, items[j].box)) continue;
        if (search_.belongs_to_uncertified(items[i].face, items[j].face)) {
          search_.judge(items[i].face, items[j].face, tally);
        }
      }
    }
  }

 private:
  const PairSearch& search_;
};

/// Faces on a finer level than others look themselves up on every coarser level; a pair
/// belongs to the cell of the low corner of the boxes' intersection.
void PairSearch::cross_levels(const FaceGrid& grid, unsigned thread) {
  const auto [first, last] = slice(thread);
  Tally& tally = tallies_[thread];
  for (std::size_t f = first; f < last; ++f) {
    const auto t = static_cast<std::uint32_t>(f);
    if (!grid.placed(t)) continue;
    const FloatBox& box = boxes_[t];
    for (const std::int32_t level : grid.levels()) {
      if (level <= grid.level(t)) continue;
      const CellRange range = grid.cells(box, level);
      for (std::int32_t x = range.low[0]; x <= range.high[0]; ++x) {
        for (std::int32_t y = range.low[1]; y <= range.high[1]; ++y) {
          for (std::int32_t z = range.low[2]; z <= range.high[2]; ++z) {
            grid.for_each_in({level, x, y, z}, [&](std::uint32_t u, std::uint32_t corner) {
              const bool owns = (x == range.low[0] || (corner & 1u) == 0) &&
                                (y == range.low[1] || (corner & 2u) == 0) &&
                                (z == range.low[2] || (corner & 4u) == 0);
              if (owns && boxes_overlap(box, boxes_[u]) && belongs_to_uncertified(t, u)) {
                judge(t, u, tally);
              }
            });
          }
        }
      }
    }
  }
}

/// The pairs of the faces not covered by certificates, from the fine grid.
void PairSearch::find_pairs(double cell) {
  if (!any_active_) return;
  std::vector<std::uint8_t> include(faces_.size());
  for (std::size_t t = 0; t < faces_.size(); ++t) {
    include[t] = active_[t] != 0 && collinear_[t] == 0 ? 1 : 0;
  }
  FaceGrid grid(boxes_, include, 1.0 / cell, FaceGrid::kMaxLevels, threads_);
  PairVisitor visitor(*this);
  grid.visit(visitor);
  if (grid.levels().size() > 1) {
    on_threads(threads_, [&](unsigned thread) { cross_levels(grid, thread); });
  }
  // Faces spanning more than two cells on every level (coordinates near the float range):
  // against every other face in the grid.
  const std::vector<std::uint32_t>& oversized = grid.oversized();
  on_threads(threads_, [&](unsigned thread) {
    Tally& tally = tallies_[thread];
    for (std::size_t w = thread; w < oversized.size(); w += threads_) {
      const std::uint32_t t = oversized[w];
      for (std::uint32_t u = 0; u < faces_.size(); ++u) {
        if (include[u] == 0 || u == t || (!grid.placed(u) && u < t)) continue;
        if (boxes_overlap(boxes_[t], boxes_[u]) && belongs_to_uncertified(t, u)) {
          judge(t, u, tally);
        }
      }
    }
  });
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
    out.regions += tally.regions;
    out.certified += tally.certified;
  }
  out.collinear = std::move(collinear_);
  return out;
}

FacePairs PairSearch::run() {
  const std::size_t n = faces_.size();
  collinear_.assign(n, 0);
  active_.assign(n, 0);
  const double extent = median_extent();
  if (options_.certify) certify_regions(kCoarseCellsPerExtent * extent);
  if (!certifying_) std::fill(active_.begin(), active_.end(), std::uint8_t{1});
  if (any_active_) {
    // Per face, but only when some face is left for the fine grid (their pages cost time).
    boxes_.resize(n);
    planes_.resize(n);
    in_range_.resize(n);
    if (certifying_) low_cell_.resize(n);
    on_threads(threads_, [this](unsigned thread) { prepare(thread); });
  }
  find_pairs(kFineCellsPerExtent * extent);
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
  if (mesh.triangles.size() >= (std::size_t{1} << 29)) {
    throw std::length_error("find_face_pairs: more than 2^29 - 1 faces");
  }
  return PairSearch(mesh, triangle_part, parts, exact, options).run();
}

}  // namespace tumble::engine::detail
