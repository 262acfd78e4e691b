// Parts that cross, nest, touch, repeat or intersect themselves (engine/src/part_overlap.hpp,
// overlap_policy.hpp): exact verdicts, independent of scale and of the order of the parts.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "base/errors.hpp"
#include "engine/geometry/primitive_meshes.hpp"
#include "engine/mass/mesh_analysis.hpp"
#include "engine/mesh_fixtures.hpp"
#include "support/input_error.hpp"

namespace tumble::engine {
namespace {

using ::testing::AllOf;
using ::testing::Contains;
using ::testing::Each;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using ::testing::Not;

/// The axis-aligned box [low, high], outward.
TriangleMesh box(const Eigen::Vector3d& low, const Eigen::Vector3d& high) {
  TriangleMesh mesh = box_mesh(high - low);
  transform_mesh(mesh, Eigen::Matrix3d::Identity(), 0.5 * (low + high));
  return mesh;
}

using mesh_fixtures::joined;
using mesh_fixtures::reversed;

MassOptions allowing(double scale = 1.0) {
  MassOptions options;
  options.overlap = OverlapMode::kSum;
  options.scale = Eigen::Vector3d::Constant(scale);
  return options;
}

MassOptions strict(double scale = 1.0) {
  MassOptions options;
  options.overlap = OverlapMode::kRefuse;
  options.scale = Eigen::Vector3d::Constant(scale);
  return options;
}

std::string error_of(const TriangleMesh& mesh, const MassOptions& options = strict()) {
  return tumble::testing::input_error_of([&] { analyze_mesh(mesh, options, "parts.stl"); },
                                         "the mesh");
}

/// The volume a message states, "(V m^3)".
double stated_volume(const std::string& message) {
  const std::size_t end = message.find(" m^3)");
  EXPECT_NE(end, std::string::npos) << message;
  if (end == std::string::npos) return -1.0;
  const std::size_t start = message.rfind('(', end) + 1;
  return std::strtod(message.substr(start, end - start).c_str(), nullptr);
}

// Two 2 x 2 x 2 boxes, the second moved by (1, 0.5, 0.25): they share a box of
// 1 x 1.5 x 1.75 = 2.625 m^3, which the sum counts twice.
const Eigen::Vector3d kShift(1.0, 0.5, 0.25);
TriangleMesh crossing_boxes() {
  return joined(box({0, 0, 0}, {2, 2, 2}), box(kShift, kShift + Eigen::Vector3d(2, 2, 2)));
}
constexpr double kShared = 1.0 * 1.5 * 1.75;

TEST(PartOverlap, CrossingBoxesAreAnErrorNamingTheParts) {
  const std::string error = error_of(crossing_boxes());
  EXPECT_THAT(
      error, AllOf(HasSubstr("parts.stl: parts 1 and 2 of 2 overlap (their surfaces "
                             "cross), so their shared volume ("),
                   HasSubstr("would count twice; give --overlap union to take their exact union")));
  EXPECT_NEAR(stated_volume(error), kShared, 1e-5 * kShared);  // printed to 6 digits
}

TEST(PartOverlap, AllowedCrossingWarnsWithTheExactSharedVolume) {
  const MeshReport report = analyze_mesh(crossing_boxes(), allowing(), "parts.stl");
  EXPECT_NEAR(report.volume, 16.0, 1e-12 * 16.0);  // both boxes, as the warning says
  ASSERT_THAT(report.warnings, ElementsAre(HasSubstr("parts 1 and 2 of 2 overlap")));
  EXPECT_THAT(report.warnings[0], HasSubstr("counts twice"));
  EXPECT_NEAR(stated_volume(report.warnings[0]), kShared, 1e-5 * kShared);
}

TEST(PartOverlap, TheVerdictDoesNotDependOnScaleOrOrder) {
  const TriangleMesh a = box({0, 0, 0}, {2, 2, 2});
  const TriangleMesh b = box(kShift, kShift + Eigen::Vector3d(2, 2, 2));
  for (const double scale : {1e-6, 1.0, 1e6}) {
    for (const TriangleMesh& mesh : {joined(a, b), joined(b, a)}) {
      EXPECT_THAT(error_of(mesh, strict(scale)), HasSubstr("parts 1 and 2 of 2 overlap")) << scale;
      const MeshReport report = analyze_mesh(mesh, allowing(scale), "parts.stl");
      ASSERT_EQ(report.warnings.size(), 1u) << scale;
      const double shared = kShared * scale * scale * scale;
      EXPECT_NEAR(stated_volume(report.warnings[0]), shared, 1e-5 * shared) << scale;
    }
  }
}

TEST(PartOverlap, BoxInsideABoxFacingTheSameWayIsAnOverlap) {
  const TriangleMesh outer = box({0, 0, 0}, {4, 3, 2}), inner = box({1, 1, 0.5}, {3, 2, 1.5});
  for (const TriangleMesh& mesh : {joined(outer, inner), joined(inner, outer)}) {
    const std::string error = error_of(mesh);
    EXPECT_THAT(error, HasSubstr("lies inside another part with the same orientation"));
    EXPECT_NEAR(stated_volume(error), 2.0, 1e-6);
    const MeshReport report = analyze_mesh(mesh, allowing(), "nested.stl");
    EXPECT_NEAR(report.volume, 24.0 + 2.0, 1e-12 * 26.0);
    EXPECT_THAT(report.warnings, ElementsAre(HasSubstr("counts twice")));
  }
}

TEST(PartOverlap, BoxInsideABoxFacingTheOtherWayIsACavity) {
  const TriangleMesh outer = box({0, 0, 0}, {4, 3, 2});
  const TriangleMesh inner = reversed(box({1, 1, 0.5}, {3, 2, 1.5}));
  for (const double scale : {1e-6, 1.0, 1e6}) {
    for (const TriangleMesh& mesh : {joined(outer, inner), joined(inner, outer)}) {
      const MeshReport report = analyze_mesh(mesh, strict(scale), "hollow.stl");
      EXPECT_EQ(report.cavities, 1u);
      EXPECT_THAT(report.warnings, IsEmpty());
      const double volume = (24.0 - 2.0) * scale * scale * scale;
      EXPECT_NEAR(report.volume, volume, 1e-12 * volume);
    }
  }
}

TEST(PartOverlap, CavityTouchingTheOuterWallIsStillACavity) {
  // The cavity [0, 1]^3 shares three face planes with the outer box [0, 2]^3: the matter is an
  // L-shaped solid of 7 m^3, its wall of zero thickness there.
  const TriangleMesh mesh =
      joined(box({0, 0, 0}, {2, 2, 2}), reversed(box({0, 0, 0.5}, {1, 1, 1})));
  const MeshReport report = analyze_mesh(mesh, strict(), "flush.stl");
  EXPECT_EQ(report.cavities, 1u);
  EXPECT_NEAR(report.volume, 8.0 - 0.5, 1e-12 * 8.0);
}

TEST(PartOverlap, CavityReachingOutsideIsAnError) {
  const TriangleMesh mesh =
      joined(box({0, 0, 0}, {2, 2, 2}), reversed(box({1, 1, 1}, {3, 1.5, 1.5})));
  const std::string error = error_of(mesh);
  EXPECT_THAT(error,
              AllOf(HasSubstr("parts 1 and 2 of 2 overlap"), HasSubstr("as a cavity would")));
  EXPECT_NEAR(stated_volume(error), 1.0 * 0.5 * 0.5, 1e-6);  // the part of it outside
}

TEST(PartOverlap, BoxesSharingAFaceOnlyTouch) {
  // Welded into one part with an inner double wall (the same four corners), or two parts
  // whose faces meet in one plane: either way no overlap, and the volume is the sum.
  const TriangleMesh a = box({0, 0, 0}, {1, 1, 1});
  for (const TriangleMesh& other :
       {box({1, 0, 0}, {2, 1, 1}), box({1, -0.5, -0.25}, {3, 1.5, 1.5}),
        box({1, 0.25, 0.25}, {1.5, 0.75, 0.75}), box({0.25, 0.25, 1}, {0.75, 2, 1.5})}) {
    for (const double scale : {1e-6, 1.0, 1e6}) {
      for (const TriangleMesh& mesh : {joined(a, other), joined(other, a)}) {
        const MeshReport report = analyze_mesh(mesh, strict(scale), "stack.stl");
        const double volume =
            (1.0 + std::abs(analyze_mesh(other, {}, "b").volume)) * scale * scale * scale;
        EXPECT_NEAR(report.volume, volume, 1e-12 * volume);
        EXPECT_THAT(report.warnings, Each(Not(HasSubstr("overlap"))));
      }
    }
  }
}

TEST(PartOverlap, BoxesTouchingAtAnEdgeOrAVertexOnlyTouch) {
  const TriangleMesh a = box({0, 0, 0}, {1, 1, 1});
  for (const TriangleMesh& other :
       {box({1, 1, 0}, {2, 2, 1}),      // a whole edge, welded into one part
        box({1, 1, 0.5}, {2, 2, 1.5}),  // half an edge, two parts
        box({1, 1, 1}, {2, 2, 2}),      // a corner, welded
        box({1, 0.5, 1}, {2, 1.5, 2}),  // an edge along a face's edge, two parts
        tetrahedron_mesh({Eigen::Vector3d(1, 0.5, 0.5), Eigen::Vector3d(2, 0, 0),
                          Eigen::Vector3d(2, 1, 0), Eigen::Vector3d(2, 0.5, 1)})}) {  // a point
    for (const TriangleMesh& mesh : {joined(a, other), joined(other, a)}) {
      const MeshReport report = analyze_mesh(mesh, strict(), "touch.stl");
      const double volume = 1.0 + analyze_mesh(other, {}, "b").volume;
      EXPECT_NEAR(report.volume, volume, 1e-12 * volume);
      EXPECT_THAT(report.warnings, Each(Not(HasSubstr("overlap"))));
    }
  }
}

TEST(PartOverlap, ADuplicatedCubeCountsTwice) {
  // The same cube twice at the same place (assimp-testmodels XGL/sample_official.xgl): welded
  // into one part whose every face is there twice.
  const TriangleMesh cube = box({0, 0, 0}, {1, 1, 1});
  const std::string error = error_of(joined(cube, cube));
  EXPECT_THAT(error, HasSubstr("part 1 of 1 repeats itself: the same surface twice at the same "
                               "place (12 pairs of faces repeated with the same orientation)"));
  EXPECT_NEAR(stated_volume(error), 1.0, 1e-12);
  const MeshReport report = analyze_mesh(joined(cube, cube), allowing(), "twice.stl");
  EXPECT_NEAR(report.volume, 2.0, 1e-12);
  EXPECT_THAT(report.warnings, Contains(HasSubstr("repeats itself")));
}

TEST(PartOverlap, ACubeAndItsMirrorImageCancel) {
  // Nothing is left: zero volume, and the message says why.
  const TriangleMesh cube = box({0, 0, 0}, {1, 1, 1});
  for (const MassOptions& options : {strict(), allowing()}) {
    EXPECT_THAT(error_of(joined(cube, reversed(cube)), options),
                HasSubstr("parts.stl: encloses zero volume (part 1 of 1 is a surface and its "
                          "mirror image at the same place (12 pairs of faces repeated with "
                          "opposite orientations): the two cancel, so it adds no volume); for a "
                          "thin sheet use --shell THICKNESS"));
  }
  // Beside another solid, the cancelled pair adds nothing, as the warning says.
  const TriangleMesh mesh = joined(joined(cube, reversed(cube)), box({3, 0, 0}, {4, 2, 1}));
  const MeshReport report = analyze_mesh(mesh, strict(), "mirrored.stl");
  EXPECT_NEAR(report.volume, 2.0, 1e-12);
  EXPECT_THAT(report.warnings, Contains(HasSubstr("the two cancel, so it adds no volume")));

  // The copy's corner off by rounding (BLEND/MirroredCube_252.blend): not welded, its faces
  // cross the original's, yet the part encloses nothing: still a surface and its mirror image.
  TriangleMesh copy = reversed(cube);
  copy.positions[0] += Eigen::Vector3d(1e-9, 2e-9, -1e-9);
  const TriangleMesh rounded = joined(joined(cube, copy), box({3, 0, 0}, {4, 2, 1}));
  const MeshReport approximate = analyze_mesh(rounded, strict(), "mirrored.stl");
  EXPECT_NEAR(approximate.volume, 2.0, 1e-8);
  EXPECT_THAT(approximate.warnings,
              Contains(HasSubstr("part 1 of 2 is a surface and an inverted copy of it at the "
                                 "same place, apart from rounding")));
}

TEST(PartOverlap, ASelfIntersectingPartIsAnError) {
  // A box and a tetrahedron sharing the box's corner (2, 2, 2): one connected part, whose
  // tetrahedron reaches into the box through its top face.
  const TriangleMesh mesh =
      joined(box({0, 0, 0}, {2, 2, 2}),
             tetrahedron_mesh({Eigen::Vector3d(2, 2, 2), Eigen::Vector3d(0.5, 1, 3),
                               Eigen::Vector3d(1, 0.5, 3), Eigen::Vector3d(1, 1, 1)}));
  for (const double scale : {1e-6, 1.0, 1e6}) {
    EXPECT_THAT(error_of(mesh, strict(scale)), HasSubstr("part 1 of 1 intersects itself ("));
    const MeshReport report = analyze_mesh(mesh, allowing(scale), "fused.stl");
    EXPECT_THAT(report.warnings, Contains(HasSubstr("intersects itself")));
    // --overlap union (the default) refuses it too, saying why: the exact union needs parts
    // free of self-intersections.
    MassOptions united = allowing(scale);
    united.overlap = OverlapMode::kUnion;
    EXPECT_THAT(error_of(mesh, united),
                AllOf(HasSubstr("part 1 of 1 intersects itself ("),
                      HasSubstr("their exact union cannot be computed (it needs closed, outward "
                                "parts free of self-intersections): give --overlap sum")));
  }
}

TEST(PartOverlap, ManyDisjointPartsAreClean) {
  TriangleMesh mesh;
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) {
      const Eigen::Vector3d low(2.0 * i, 2.0 * j, (i + j) % 2);
      append_mesh(mesh, box(low, low + Eigen::Vector3d(1.5, 1.5, 1.5)));
    }
  }
  const MeshReport report = analyze_mesh(mesh, strict(), "grid.stl");
  EXPECT_EQ(report.parts, 36u);
  EXPECT_NEAR(report.volume, 36 * 3.375, 1e-12 * 36 * 3.375);
  EXPECT_THAT(report.warnings, IsEmpty());
}

TEST(PartOverlap, ShellModeSkipsTheVolumeChecks) {
  MassOptions options;
  options.shell_thickness = 0.01;
  const MeshReport report = analyze_mesh(crossing_boxes(), options, "sheets.stl");
  EXPECT_THAT(report.warnings, IsEmpty());
  EXPECT_NEAR(report.area, 48.0, 1e-12 * 48.0);
}

}  // namespace
}  // namespace tumble::engine
