// Exact intersection tests between and within parts (part_overlap.hpp).
//
// Every decision is a sign of a determinant, exact (Shewchuk 1997; the triangle-triangle test
// of Guigue and Devillers 2003), so it is the same at any scale and for any order of the
// parts. Three passes:
// 1. every pair of faces whose boxes overlap is judged (face_pairs.hpp finds them with a grid
//    and decides most with a certified floating-point filter; what it cannot decide comes
//    back here, to judge()): within a part, two faces cross where they meet beyond their
//    shared vertices (a face sharing one vertex with the other meets it beyond that vertex
//    only if its opposite edge reaches the other face) and pass through each other; faces that
//    only touch along their boundaries, or lie in one plane, are not judged a crossing
//    (judge_same_part says why); the same face twice is a repeat (same orientation) or a
//    mirror image (opposite); faces of two parts meet or do not;
// 2. between parts whose surfaces meet, the corefined Boolean of the two solids (PMP) says
//    whether the volumes overlap (a non-empty result) or only touch (an empty one);
// 3. containment: the exact winding number of one part around a vertex of the other, by a ray
//    whose every crossing is a clean pass through a face's interior (else another ray).
// The reference method of pass 1 (tests) finds the pairs with CGAL::box_self_intersection_d
// (Zomorodian and Edelsbrunner 2002) and judges each here.
#include "engine/overlap/part_overlap.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <utility>

#include "face_pairs.hpp"

namespace tumble::engine::detail {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Triangle = Kernel::Triangle_3;
using Segment = Kernel::Segment_3;
using Ray = Kernel::Ray_3;
using Vector = Kernel::Vector_3;
using SurfaceMesh = CGAL::Surface_mesh<Point>;
using Face = std::array<std::uint32_t, 3>;

/// What pass 1 found in one part, and the part's extent.
struct PartTally {
  std::size_t triangles = 0;       ///< non-degenerate ones
  std::size_t repeated = 0;        ///< pairs of the same face, same orientation
  std::size_t mirrored = 0;        ///< pairs of the same face, opposite orientations
  std::size_t crossing = 0;        ///< pairs that cross or fold onto each other
  double signed_volume = 0.0;      ///< times 6, about the part's first vertex
  double absolute_volume = 0.0;    ///< sum of |det|: the rounding scale of signed_volume
  std::uint32_t first_vertex = 0;  ///< reference of signed_volume
  Eigen::AlignedBox3d box;
  std::vector<std::uint32_t> faces;  ///< its triangles
};

class Analysis final : public ExactFaceTests {
 public:
  Analysis(const TriangleMesh& mesh, const std::vector<std::uint32_t>& triangle_part,
           std::size_t parts)
      : mesh_(mesh), faces_(mesh.triangles), triangle_part_(triangle_part), parts_(parts) {}
  PartOverlaps run(const OverlapOptions& options);

  bool collinear(std::uint32_t t) const override {
    const Face& f = faces_[t];
    return CGAL::collinear(point(f[0]), point(f[1]), point(f[2]));
  }
  PairVerdict judge(std::uint32_t t, std::uint32_t u) const override;

 private:
  void tally_parts();
  FacePairs reference_pairs() const;
  PairVerdict judge_same_part(std::uint32_t t, std::uint32_t u) const;
  bool straddles(const Face& a, const Face& b) const;
  void part_findings(PartOverlaps& out) const;
  void judge_parts(std::uint32_t i, std::uint32_t j, PartOverlaps& out);
  bool judge_meeting(std::uint32_t i, std::uint32_t j, std::size_t pairs, PartOverlaps& out);
  std::optional<int> winding(std::uint32_t part, const Point& p) const;
  std::optional<int> winding_around_part(std::uint32_t outer, std::uint32_t inner) const;
  const SurfaceMesh* surface(std::uint32_t part);
  Point point(std::uint32_t v) const {
    const Eigen::Vector3d& p = mesh_.positions[v];
    return {p.x(), p.y(), p.z()};
  }
  Triangle triangle(std::uint32_t t) const {
    const Face& f = faces_[t];
    return {point(f[0]), point(f[1]), point(f[2])};
  }

  const TriangleMesh& mesh_;
  const std::vector<Face>& faces_;
  const std::vector<std::uint32_t>& triangle_part_;
  std::vector<std::uint8_t> degenerate_;
  std::vector<PartTally> parts_;
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> meeting_;  ///< pairs of faces
  std::map<std::uint32_t, std::optional<SurfaceMesh>> surfaces_;            ///< built lazily
};

/// Each part's faces, box and signed volume (the counts of pass 1 are already there).
void Analysis::tally_parts() {
  for (std::uint32_t t = 0; t < faces_.size(); ++t) {
    PartTally& part = parts_[triangle_part_[t]];
    const Face& f = faces_[t];
    if (part.faces.empty()) part.first_vertex = f[0];
    part.faces.push_back(t);
    const Eigen::Vector3d& r = mesh_.positions[part.first_vertex];
    const Eigen::Vector3d a = mesh_.positions[f[0]] - r, b = mesh_.positions[f[1]] - r,
                          c = mesh_.positions[f[2]] - r;
    const double det = a.dot(b.cross(c));
    part.signed_volume += det;
    part.absolute_volume += std::abs(det);
    for (const std::uint32_t v : f) part.box.extend(mesh_.positions[v]);
    if (degenerate_[t] == 0) ++part.triangles;
  }
}

/// How many vertices two faces share, and the corners of `t` holding the first shared one.
int shared_vertices(const Face& t, const Face& u, int& corner_t, int& corner_u) {
  int shared = 0;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (t[i] != u[j]) continue;
      if (shared++ == 0) corner_t = i, corner_u = j;
    }
  }
  return shared;
}

/// Whether the corners of `a` lie strictly on both sides of the plane of `b`. Corners `a`
/// shares with `b` lie on that plane and are not tested (an exact zero would defeat the
/// predicates' floating-point filter and cost an exact evaluation).
bool Analysis::straddles(const Face& a, const Face& b) const {
  bool positive = false, negative = false;
  for (const std::uint32_t v : a) {
    if (v == b[0] || v == b[1] || v == b[2]) continue;
    const CGAL::Orientation side =
        CGAL::orientation(point(b[0]), point(b[1]), point(b[2]), point(v));
    positive |= side == CGAL::POSITIVE;
    negative |= side == CGAL::NEGATIVE;
  }
  return positive && negative;
}

/// Two faces of one part cross where they meet beyond their shared vertices and pass through
/// each other: each has corners strictly on both sides of the other's plane. Faces that only
/// touch along their boundaries do not, nor do faces in one plane: an inner double wall (two
/// solids face to face) lies there, and so does a non-convex face fanned into triangles that
/// overlap and cancel, which still bounds the right volume.
PairVerdict Analysis::judge_same_part(std::uint32_t t, std::uint32_t u) const {
  const Face &ft = faces_[t], &fu = faces_[u];
  int ct = 0, cu = 0;
  const int shared = shared_vertices(ft, fu, ct, cu);
  if (shared == 3) {
    // The same face twice: the same cyclic order is a repeat, the reverse a mirror image.
    const bool same = ft[(ct + 1) % 3] == fu[(cu + 1) % 3];
    return same ? PairVerdict::kRepeated : PairVerdict::kMirrored;
  }
  // Sharing an edge, they can meet beyond it only in one plane (folded onto each other).
  if (shared == 2) return PairVerdict::kApart;
  // Passing through each other needs corners strictly on both sides of each plane: on a smooth
  // surface, most neighbours sharing a vertex fail this first, cheap test.
  if (!straddles(ft, fu) || !straddles(fu, ft)) return PairVerdict::kApart;
  const Triangle tt = triangle(t), tu = triangle(u);
  if (shared == 1) {
    // Sharing a vertex, they meet beyond it only if an opposite edge reaches the other face.
    const Segment edge_t(point(ft[(ct + 1) % 3]), point(ft[(ct + 2) % 3]));
    const Segment edge_u(point(fu[(cu + 1) % 3]), point(fu[(cu + 2) % 3]));
    if (!CGAL::do_intersect(edge_t, tu) && !CGAL::do_intersect(edge_u, tt)) {
      return PairVerdict::kApart;
    }
  } else if (!CGAL::do_intersect(tt, tu)) {
    return PairVerdict::kApart;
  }
  return PairVerdict::kCrossing;
}

PairVerdict Analysis::judge(std::uint32_t t, std::uint32_t u) const {
  if (triangle_part_[t] == triangle_part_[u]) return judge_same_part(t, u);
  // Parts share no vertex: a plain triangle test.
  return CGAL::do_intersect(triangle(t), triangle(u)) ? PairVerdict::kMeeting : PairVerdict::kApart;
}

/// Pass 1 by the reference method: CGAL's box intersection, every pair judged exactly.
FacePairs Analysis::reference_pairs() const {
  // A face's box is that of the grid (face_pairs.hpp); its id is its face's address.
  using Box = CGAL::Box_intersection_d::Box_with_handle_d<float, 3, const Face*,
                                                          CGAL::Box_intersection_d::ID_FROM_HANDLE>;
  FacePairs pairs;
  pairs.parts.resize(parts_.size());
  pairs.collinear.resize(faces_.size());
  std::vector<Box> boxes;
  for (std::uint32_t t = 0; t < faces_.size(); ++t) {
    pairs.collinear[t] = collinear(t) ? 1 : 0;
    if (pairs.collinear[t] != 0) continue;
    FloatBox box = face_box(mesh_, t);
    boxes.emplace_back(box.lo, box.hi, &faces_[t]);
  }
  pairs.deferred_faces = faces_.size();
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& a, const Box& b) {
    const auto t = static_cast<std::uint32_t>(a.handle() - faces_.data());
    const auto u = static_cast<std::uint32_t>(b.handle() - faces_.data());
    ++pairs.candidates;
    switch (judge(t, u)) {
      case PairVerdict::kApart:
        break;
      case PairVerdict::kRepeated:
        ++pairs.parts[triangle_part_[t]].repeated;
        break;
      case PairVerdict::kMirrored:
        ++pairs.parts[triangle_part_[t]].mirrored;
        break;
      case PairVerdict::kCrossing:
        ++pairs.parts[triangle_part_[t]].crossing;
        break;
      case PairVerdict::kMeeting:
        ++pairs.meeting[std::minmax(triangle_part_[t], triangle_part_[u])];
        break;
    }
  });
  pairs.deferred = pairs.candidates;
  return pairs;
}
/// The winding number of `part`'s faces (as wound) around `p`: +1 inside an outward part, -1
/// inside an inward one, 0 outside; none when `p` is on its surface or every ray grazed an edge.
std::optional<int> Analysis::winding(std::uint32_t part, const Point& p) const {
  static const std::array<Vector, 6> directions = {
      Vector(0.8191, 0.3412, 0.4611),   Vector(-0.2711, 0.9139, 0.3023),
      Vector(0.1313, -0.4721, 0.8718),  Vector(-0.6547, -0.5291, -0.5397),
      Vector(0.4217, -0.8117, -0.1019), Vector(-0.1931, 0.2087, -0.9571)};
  for (const std::uint32_t f : parts_[part].faces) {
    if (!degenerate_[f] && triangle(f).has_on(p)) return std::nullopt;
  }
  for (const Vector& direction : directions) {
    const Ray ray(p, direction);
    int total = 0;
    bool clean = true;
    for (const std::uint32_t f : parts_[part].faces) {
      if (degenerate_[f]) continue;
      const Triangle t = triangle(f);
      if (!CGAL::do_intersect(ray, t)) continue;
      const CGAL::Orientation side = CGAL::orientation(t[0], t[1], t[2], p);
      clean = side != CGAL::COPLANAR && !CGAL::do_intersect(ray, Segment(t[0], t[1])) &&
              !CGAL::do_intersect(ray, Segment(t[1], t[2])) &&
              !CGAL::do_intersect(ray, Segment(t[2], t[0]));
      if (!clean) break;
      total += side == CGAL::NEGATIVE ? 1 : -1;  // the face's normal points away from p
    }
    if (clean) return total;
  }
  return std::nullopt;
}

/// The winding of `outer` around a vertex of `inner` that is not on its surface: up to 64
/// corners spread over `inner`'s faces are tried.
std::optional<int> Analysis::winding_around_part(std::uint32_t outer, std::uint32_t inner) const {
  const std::vector<std::uint32_t>& faces = parts_[inner].faces;
  const std::size_t corners = 3 * faces.size();
  const std::size_t tries = std::min<std::size_t>(corners, 64);
  for (std::size_t i = 0; i < tries; ++i) {
    const std::size_t corner = i * corners / tries;
    if (const auto w = winding(outer, point(faces_[faces[corner / 3]][corner % 3]))) return w;
  }
  return std::nullopt;
}

/// Part `part` as an outward-wound Surface_mesh for the Boolean operations; none when its
/// faces do not form a 2-manifold (CGAL's halfedge structure cannot hold it).
const SurfaceMesh* Analysis::surface(std::uint32_t part) {
  auto [slot, added] = surfaces_.try_emplace(part);
  if (!added) return slot->second ? &*slot->second : nullptr;
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  std::map<std::uint32_t, std::size_t> index;
  for (const std::uint32_t f : parts_[part].faces) {
    std::vector<std::size_t>& polygon = polygons.emplace_back();
    for (const std::uint32_t v : faces_[f]) {
      const auto [it, fresh] = index.try_emplace(v, points.size());
      if (fresh) points.push_back(point(v));
      polygon.push_back(it->second);
    }
  }
  if (!PMP::is_polygon_soup_a_polygon_mesh(polygons)) return nullptr;
  SurfaceMesh& mesh = slot->second.emplace();
  PMP::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  if (parts_[part].signed_volume < 0.0) PMP::reverse_face_orientations(mesh);
  return &mesh;
}

OverlapFinding make_finding(OverlapKind kind, std::uint32_t first, std::uint32_t second,
                            std::size_t face_pairs) {
  OverlapFinding finding;
  finding.kind = kind;
  finding.first = first;
  finding.second = second;
  finding.face_pairs = face_pairs;
  return finding;
}

/// The volume of the Boolean intersection (or difference a - b) of two closed, outward,
/// non-self-intersecting solids: 0 when it is empty (the solids at most touch); none when CGAL
/// could not compute it.
std::optional<double> boolean_volume(const SurfaceMesh& a, const SurfaceMesh& b,
                                     bool intersection) {
  SurfaceMesh first = a, second = b, result;  // corefinement changes its inputs
  try {
    const bool done = intersection ? PMP::corefine_and_compute_intersection(first, second, result)
                                   : PMP::corefine_and_compute_difference(first, second, result);
    if (!done) return std::nullopt;
  } catch (const std::exception&) {
    return std::nullopt;
  }
  if (result.number_of_faces() == 0) return 0.0;
  const double volume = PMP::volume(result);
  if (!(volume > 0.0)) return std::nullopt;  // faces enclosing nothing: not a clear answer
  return volume;
}

/// Parts i < j whose surfaces meet at `pairs` pairs of faces: touching only, or overlapping.
/// Facing the same way, their volumes overlap where the intersection of the solids is not
/// empty; facing opposite ways, the smaller (a cavity) must lie within the other. Returns
/// whether two parts facing the same way were found to overlap (then they are not also nested).
bool Analysis::judge_meeting(std::uint32_t i, std::uint32_t j, std::size_t pairs,
                             PartOverlaps& out) {
  const bool same = (parts_[i].signed_volume > 0.0) == (parts_[j].signed_volume > 0.0);
  const bool j_smaller = std::abs(parts_[j].signed_volume) <= std::abs(parts_[i].signed_volume);
  const std::uint32_t small = j_smaller ? j : i, large = j_smaller ? i : j;
  const auto clean = [this](std::uint32_t part) {
    return parts_[part].crossing == 0 && parts_[part].repeated == 0;
  };
  std::optional<double> volume;
  if (clean(i) && clean(j)) {
    const SurfaceMesh* a = surface(same ? i : small);
    const SurfaceMesh* b = a ? surface(same ? j : large) : nullptr;
    if (a && b) volume = boolean_volume(*a, *b, same);
  }
  if (volume && *volume == 0.0) return false;  // they only touch
  OverlapFinding finding =
      make_finding(volume ? OverlapKind::kCross : OverlapKind::kUndecided, i, j, pairs);
  finding.shared_volume = volume;
  finding.cavity = !same;
  if (!same) finding.first = large, finding.second = small;
  if (!volume && same) {
    // No Boolean: a vertex of one strictly inside the other still proves an overlap.
    const auto inside = [this](std::uint32_t outer, std::uint32_t inner) {
      const auto w = winding_around_part(outer, inner);
      return w && *w != 0;
    };
    if (inside(i, j) || inside(j, i)) finding.kind = OverlapKind::kCross;
  }
  out.findings.push_back(finding);
  return same;
}

void Analysis::judge_parts(std::uint32_t i, std::uint32_t j, PartOverlaps& out) {
  if (const auto meeting = meeting_.find({i, j}); meeting != meeting_.end()) {
    if (judge_meeting(i, j, meeting->second, out)) return;
  }
  if (const auto w = winding_around_part(j, i); w && *w != 0) out.nesting.push_back({i, j, *w});
  if (const auto w = winding_around_part(i, j); w && *w != 0) out.nesting.push_back({j, i, *w});
}

/// The findings within each part.
void Analysis::part_findings(PartOverlaps& out) const {
  for (std::uint32_t i = 0; i < parts_.size(); ++i) {
    const PartTally& part = parts_[i];
    OverlapFinding finding =
        make_finding(OverlapKind::kSelfIntersection, i, i, part.crossing + part.repeated);
    if (part.triangles > 0 && 2 * part.repeated == part.triangles) {
      finding.kind = OverlapKind::kDuplicate;
      finding.shared_volume = std::abs(part.signed_volume) / 12.0;  // half of it, det / 6
    } else if (part.triangles > 0 && 2 * part.mirrored == part.triangles) {
      finding = make_finding(OverlapKind::kCancelling, i, i, part.mirrored);
    } else if (part.repeated == 0 && finding.face_pairs > 0 &&
               std::abs(part.signed_volume) <= 1e-6 * part.absolute_volume) {
      // Crossing faces and no volume: a surface and an inverted copy at the same place whose
      // vertices differ by rounding (or triangulated another way), not matter counted twice.
      finding.kind = OverlapKind::kCancelling;
      finding.approximate = true;
    } else if (finding.face_pairs == 0) {
      continue;
    }
    out.findings.push_back(finding);
  }
}

PartOverlaps Analysis::run(const OverlapOptions& options) {
  PartOverlaps out;
  bool found = false;
  if (options.face_pairs) {
    FacePairOptions search;
    search.threads = std::max(1u, options.threads);
    search.certify = options.method == FacePairMethod::kCertified;
    search.filter = options.method != FacePairMethod::kExact;
    search.bounds = options.bounds;
    FacePairs pairs = options.method == FacePairMethod::kReference
                          ? reference_pairs()
                          : find_face_pairs(mesh_, triangle_part_, parts_.size(), *this, search);
    out.stats = {pairs.candidates, pairs.deferred, pairs.deferred_faces, pairs.regions,
                 pairs.certified};
    for (std::size_t i = 0; i < parts_.size(); ++i) {
      parts_[i].repeated = pairs.parts[i].repeated;
      parts_[i].mirrored = pairs.parts[i].mirrored;
      parts_[i].crossing = pairs.parts[i].crossing;
      found |= pairs.parts[i].repeated + pairs.parts[i].mirrored + pairs.parts[i].crossing > 0;
    }
    meeting_ = std::move(pairs.meeting);
    degenerate_ = std::move(pairs.collinear);
  } else if (parts_.size() > 1) {
    degenerate_.resize(faces_.size());
    for (std::uint32_t t = 0; t < faces_.size(); ++t) degenerate_[t] = collinear(t) ? 1 : 0;
  }
  // One part and nothing found in it: nothing more to judge.
  if (parts_.size() < 2 && !found) return out;
  tally_parts();
  part_findings(out);
  if (parts_.size() < 2) return out;

  // Part pairs whose boxes overlap, in order (the findings' order is the parts'); parts whose
  // boxes are disjoint are never compared.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> candidates;
  using PartBox =
      CGAL::Box_intersection_d::Box_with_handle_d<double, 3, const PartTally*,
                                                  CGAL::Box_intersection_d::ID_FROM_HANDLE>;
  std::vector<PartBox> part_boxes;
  for (const PartTally& part : parts_) {
    const Eigen::Vector3d &low = part.box.min(), &high = part.box.max();
    part_boxes.emplace_back(CGAL::Bbox_3(low.x(), low.y(), low.z(), high.x(), high.y(), high.z()),
                            &part);
  }
  CGAL::box_self_intersection_d(
      part_boxes.begin(), part_boxes.end(), [&](const PartBox& a, const PartBox& b) {
        candidates.push_back(std::minmax(static_cast<std::uint32_t>(a.handle() - parts_.data()),
                                         static_cast<std::uint32_t>(b.handle() - parts_.data())));
      });
  std::sort(candidates.begin(), candidates.end());
  for (const auto& [i, j] : candidates) judge_parts(i, j, out);
  return out;
}

}  // namespace

PartOverlaps find_part_overlaps(const TriangleMesh& mesh,
                                const std::vector<std::uint32_t>& triangle_part, std::size_t parts,
                                const OverlapOptions& options) {
  Analysis analysis(mesh, triangle_part, parts);
  return analysis.run(options);
}

}  // namespace tumble::engine::detail
