#pragma once
// Exact intersection tests between and within the parts of a closed mesh (`tumble inspect`).
//
// Private to the engine. Every verdict is that of exact predicates, so it does not depend on
// the scale of the mesh or on the order of its parts; only the volumes reported are rounded.
// The pairs of faces are judged by a floating-point filter with a certified error bound, and
// by CGAL's exact predicates (Exact_predicates_inexact_constructions_kernel) only where the
// filter cannot tell (src/face_pairs.hpp); the one translation unit that includes CGAL is
// part_overlap.cpp (CGAL compiles slowly, so no other file sees it).

#include <cstddef>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "engine/geometry/triangle_mesh.hpp"

namespace tumble::engine::detail {

/// What was found within one part, or between two whose surfaces meet.
enum class OverlapKind {
  kSelfIntersection,  ///< faces of one part cross (or overlap in one plane, facing one way)
  kDuplicate,         ///< every face of the part is there twice, same place and orientation
  kCancelling,        ///< the part is a surface and its mirror image: no volume
  kCross,             ///< the surfaces of two parts cross: their volumes overlap
  kUndecided,         ///< the surfaces of two parts meet; touch or cross could not be decided
};

struct OverlapFinding {
  OverlapKind kind = OverlapKind::kCross;
  std::uint32_t first = 0;              ///< part, 0-based
  std::uint32_t second = 0;             ///< the other part (equal to `first` within a part)
  std::size_t face_pairs = 0;           ///< pairs of faces that cross or repeat
  std::optional<double> shared_volume;  ///< m^3 counted twice, where it could be computed
  /// kCross of two parts facing opposite ways: `second` (the smaller, an inward cavity or an
  /// outward part in an inward shell) reaches `shared_volume` outside `first`.
  bool cavity = false;
  /// kCancelling without exact mirror pairs: the faces cross (`face_pairs`) and the part's
  /// signed volume cancels to 1e-6 of the volume its faces span.
  bool approximate = false;
};

/// Containment between two parts whose surfaces do not cross.
struct PartNesting {
  std::uint32_t inner = 0;
  std::uint32_t outer = 0;
  int winding = 0;  ///< winding number of `outer`'s faces, as wound, around `inner`
};

/// How the pairs of faces are found and judged. All give the same verdicts.
enum class FacePairMethod {
  kCertified,  ///< regions certified whole, the other pairs as kFiltered (the default)
  kFiltered,   ///< a grid of the faces' boxes; the filter, exact predicates where it cannot tell
  kExact,      ///< the same grid; exact predicates for every pair (tests, benchmarks)
  kReference,  ///< CGAL's box intersection and exact predicates for every pair (tests)
};

struct OverlapOptions {
  unsigned threads = 1;  ///< for the pairs of faces (the reference method uses one)
  /// false: no pairs of faces are judged (no self-intersection, repeat or crossing is found);
  /// only the containment of parts in each other, which orients them, is decided.
  bool face_pairs = true;
  FacePairMethod method = FacePairMethod::kCertified;
  /// The least and greatest coordinates of the mesh's vertices, when the caller has them (the
  /// checks then need one pass over the vertices instead of two); a box that misses a vertex
  /// only costs that pass back, a box much larger than the vertices' can leave the checks
  /// without their coarse regions (slower, the same verdicts).
  std::optional<std::pair<Eigen::Vector3d, Eigen::Vector3d>> bounds;
};

/// How much work the pairs of faces took (for tests and benchmarks).
struct FacePairStats {
  std::size_t candidates = 0;      ///< pairs of faces judged one by one (boxes overlapping)
  std::size_t deferred = 0;        ///< of them, the pairs judged by the exact predicates
  std::size_t deferred_faces = 0;  ///< faces whose degeneracy the exact predicates decided
  std::size_t regions = 0;         ///< coarse cells holding faces (kCertified)
  std::size_t certified = 0;       ///< of them, those whose faces were certified apart
};

struct PartOverlaps {
  std::vector<OverlapFinding> findings;  ///< within parts by part, then pairs of parts in order
  std::vector<PartNesting> nesting;      ///< every part pair with a non-zero winding
  FacePairStats stats;
};

/// Finds self-intersections and repeated faces within each part and, between parts whose
/// bounding boxes overlap, whether their surfaces cross, only touch (a shared face plane, edge
/// or point: zero-volume contact, not an overlap), or nest. `triangle_part` numbers the parts
/// 0..parts-1; the mesh is welded, closed and consistently wound per part, with fewer than
/// 2^29 faces. Pairs of faces are found through their boxes, not by testing every pair; parts
/// whose boxes are disjoint are never compared.
PartOverlaps find_part_overlaps(const TriangleMesh& mesh,
                                const std::vector<std::uint32_t>& triangle_part, std::size_t parts,
                                const OverlapOptions& options = {});

}  // namespace tumble::engine::detail
