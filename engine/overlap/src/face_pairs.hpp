#pragma once
// The face pairs of part_overlap.cpp's first pass: every pair of faces whose boxes overlap,
// judged as part_overlap.cpp's exact tests would judge it, in a fraction of their time.
//
// First, the faces touching each cell of a coarse grid (16 times the faces' median extent) are
// certified as a whole where they can be: no two of them meet beyond what they share
// (region_certificate.hpp), so every pair of them is apart. Then the pairs the certificates do
// not cover come from a fine grid over the faces' boxes (face_grid.hpp); neighbours are told
// apart by the welded vertex indices they share (faces sharing an edge are never tested, the
// same face twice is a repeat or a mirror image by its vertex order alone); the rest are
// decided by orientation signs with a certified error bound (certified_orientation.hpp)
// wherever those decide them. Only the pairs the filter cannot decide (faces that touch, lie
// in one plane, or whose coordinates lie outside the filter's range) go to the exact
// predicates, through ExactFaceTests. So the verdicts are exactly those of the exact tests.

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <utility>
#include <vector>

#include "engine/geometry/triangle_mesh.hpp"

namespace tumble::engine::detail {

/// What two faces whose boxes overlap are to each other (part_overlap.cpp defines each).
enum class PairVerdict : std::uint8_t {
  kApart,     ///< nothing to count: one part's faces that do not cross, two parts' that do not meet
  kRepeated,  ///< one part: the same three vertices in the same cyclic order
  kMirrored,  ///< one part: the same three vertices in the opposite cyclic order
  kCrossing,  ///< one part: the faces pass through each other beyond their shared vertices
  kMeeting,   ///< two parts: the faces meet (touch or cross)
};

/// The exact predicates, asked only what the filter cannot decide. Called from several
/// threads at once.
class ExactFaceTests {
 public:
  virtual ~ExactFaceTests() = default;
  /// Whether the corners of face `t` are collinear.
  virtual bool collinear(std::uint32_t t) const = 0;
  /// The verdict on faces `t` and `u` (neither collinear), of one part or of two.
  virtual PairVerdict judge(std::uint32_t t, std::uint32_t u) const = 0;
};

/// Pairs of one part's faces, by verdict.
struct PartPairCounts {
  std::size_t repeated = 0, mirrored = 0, crossing = 0;
};

/// The verdicts on all pairs, summed (the same for any number of threads).
struct FacePairs {
  std::vector<PartPairCounts> parts;  ///< per part
  /// Per pair of parts (i < j) whose faces meet: how many pairs of faces meet.
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> meeting;
  std::vector<std::uint8_t> collinear;  ///< per face: 1 when its corners are collinear
  std::size_t candidates = 0;           ///< pairs judged one by one (not within a certified region)
  std::size_t deferred = 0;             ///< of those, the pairs judged by the exact predicates
  std::size_t deferred_faces = 0;       ///< faces whose collinearity they decided
  std::size_t regions = 0;              ///< coarse cells holding faces
  std::size_t certified = 0;            ///< of them, those whose faces are certified apart
};

/// A face's box in floats, rounded outward: it contains the face.
struct FloatBox {
  float lo[3], hi[3];
};
FloatBox face_box(const TriangleMesh& mesh, std::uint32_t t);

struct FacePairOptions {
  unsigned threads = 1;
  /// Certify coarse cells' faces as a whole (region_certificate.hpp) before judging pairs.
  bool certify = true;
  /// false: every face and pair goes to the exact predicates (for tests and benchmarks).
  bool filter = true;
  /// The vertices' least and greatest coordinates, if known (OverlapOptions::bounds).
  std::optional<std::pair<Eigen::Vector3d, Eigen::Vector3d>> bounds;
};

/// Judges every pair of non-collinear faces of `mesh` whose boxes (in floats, rounded outward)
/// overlap. `triangle_part` numbers the parts 0..parts-1; the mesh is welded, without faces
/// that repeat a vertex, and has fewer than 2^29 faces.
FacePairs find_face_pairs(const TriangleMesh& mesh, const std::vector<std::uint32_t>& triangle_part,
                          std::size_t parts, const ExactFaceTests& exact,
                          const FacePairOptions& options);

}  // namespace tumble::engine::detail
