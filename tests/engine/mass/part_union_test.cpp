// --overlap union (engine/mass/src/part_union.hpp): parts that overlap, nest facing the same way
// or repeat are counted as their exact union. Oracles: inclusion-exclusion over boxes (closed
// forms for each box, its centre and inertia), the hemisphere's closed forms for a sphere through
// a box face, one copy of a duplicated part.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "engine/geometry/primitive_meshes.hpp"
#include "engine/mass/mesh_analysis.hpp"
#include "engine/mesh_fixtures.hpp"
#include "support/input_error.hpp"

namespace tumble::engine {
namespace {

using ::testing::AllOf;
using ::testing::Contains;
using ::testing::HasSubstr;

/// The axis-aligned box [low, high], outward.
TriangleMesh union_box(const Eigen::Vector3d& low, const Eigen::Vector3d& high) {
  TriangleMesh mesh = box_mesh(high - low);
  transform_mesh(mesh, Eigen::Matrix3d::Identity(), 0.5 * (low + high));
  return mesh;
}

/// Mass (density 1), first moment and inertia about the origin of the box [low, high], by
/// the closed form about its centre and the parallel-axis theorem.
struct BoxMoments {
  double mass = 0.0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();    ///< mass times centre
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  ///< about the origin
};

BoxMoments box_moments_about_origin(const Eigen::Vector3d& low, const Eigen::Vector3d& high) {
  const Eigen::Vector3d size = high - low, centre = 0.5 * (low + high);
  BoxMoments out;
  out.mass = size.prod();
  out.first = out.mass * centre;
  const Eigen::Vector3d squares = size.cwiseProduct(size);
  Eigen::Matrix3d own = Eigen::Matrix3d::Zero();
  own.diagonal() << squares.y() + squares.z(), squares.x() + squares.z(), squares.x() + squares.y();
  own *= out.mass / 12.0;
  out.inertia = own + out.mass * (centre.squaredNorm() * Eigen::Matrix3d::Identity() -
                                  centre * centre.transpose());
  return out;
}

MassOptions union_options() {
  MassOptions options;
  options.density = 1.0;
  return options;  // OverlapMode::kUnion is the default
}

void expect_matrix_near(const Eigen::Matrix3d& got, const Eigen::Matrix3d& want, double tolerance) {
  EXPECT_LE((got - want).norm(), tolerance * want.norm()) << got << "\nwant\n" << want;
}

TEST(PartUnion, TwoBoxesSharingASlabAreTheBoxTheySpan) {
  const TriangleMesh mesh =
      mesh_fixtures::joined(union_box({0, 0, 0}, {2, 1, 1}), union_box({1, 0, 0}, {3, 1, 1}));
  const MeshReport report = analyze_mesh(mesh, union_options(), "slab.stl");
  const MeshReport span = analyze_mesh(union_box({0, 0, 0}, {3, 1, 1}), union_options(), "span");
  EXPECT_NEAR(report.volume, 3.0, 1e-12 * 3.0);
  EXPECT_LE((report.mass_properties.center_of_mass - span.mass_properties.center_of_mass).norm(),
            1e-12 * 3.0);
  expect_matrix_near(report.mass_properties.inertia, span.mass_properties.inertia, 1e-12);
  EXPECT_EQ(report.overlap, OverlapMode::kUnion);
  EXPECT_EQ(report.united_parts, 2u);
  EXPECT_NEAR(report.shared_volume, 1.0, 1e-12);
  EXPECT_THAT(report.warnings,
              Contains(HasSubstr("parts 1 and 2 of 2 are taken as their exact union (--overlap "
                                 "union): their shared volume, counted once, is 1 m^3 (33.3333% "
                                 "of the mesh's volume)")));
}

TEST(PartUnion, CrossingBoxesMatchInclusionExclusion) {
  // [0, 2]^3 and the same box moved by (1, 0.5, 0.25): they share [1, 2] x [0.5, 2] x [0.25, 2].
  const Eigen::Vector3d shift(1.0, 0.5, 0.25);
  const Eigen::Vector3d two = Eigen::Vector3d::Constant(2.0);
  const TriangleMesh mesh =
      mesh_fixtures::joined(union_box({0, 0, 0}, two), union_box(shift, shift + two));
  const BoxMoments a = box_moments_about_origin({0, 0, 0}, two);
  const BoxMoments b = box_moments_about_origin(shift, shift + two);
  const BoxMoments shared = box_moments_about_origin(shift, two);
  const double mass = a.mass + b.mass - shared.mass;
  const Eigen::Vector3d centre = (a.first + b.first - shared.first) / mass;
  const Eigen::Matrix3d about_origin = a.inertia + b.inertia - shared.inertia;
  const Eigen::Matrix3d about_centre =
      about_origin -
      mass * (centre.squaredNorm() * Eigen::Matrix3d::Identity() - centre * centre.transpose());
  for (const OverlapMode mode : {OverlapMode::kUnion}) {
    MassOptions options = union_options();
    options.overlap = mode;
    const MeshReport report = analyze_mesh(mesh, options, "cross.stl");
    EXPECT_NEAR(report.volume, mass, 1e-12 * mass);
    EXPECT_LE((report.mass_properties.center_of_mass - centre).norm(), 1e-12 * 2.0);
    expect_matrix_near(report.mass_properties.inertia, about_centre, 1e-12);
    EXPECT_NEAR(report.shared_volume, shared.mass, 1e-12 * mass);
  }
  // The sum counts the shared box twice; refuse names the parts.
  MassOptions sum = union_options();
  sum.overlap = OverlapMode::kSum;
  EXPECT_NEAR(analyze_mesh(mesh, sum, "cross.stl").volume, a.mass + b.mass, 1e-12 * mass);
  MassOptions refuse = union_options();
  refuse.overlap = OverlapMode::kRefuse;
  EXPECT_THAT(tumble::testing::input_error_of([&] { analyze_mesh(mesh, refuse, "cross.stl"); }),
              HasSubstr("cross.stl: parts 1 and 2 of 2 overlap (their surfaces cross)"));
}

TEST(PartUnion, ASphereThroughABoxFaceIsTheBoxAndTheHemisphereOutside) {
  // A sphere of radius r centred on the face x = 1 of the box [-1, 1]^3: the union is the box
  // and a hemisphere (closed forms: volume 2/3 pi r^3, centre 3r/8 from the face). The
  // tessellated sphere's own volume error bounds the union's.
  const double r = 0.5;
  TriangleMesh sphere = uv_sphere_mesh(r, 48, 24);
  const double sphere_exact = 4.0 / 3.0 * std::numbers::pi * r * r * r;
  const double tessellation =
      std::abs(analyze_mesh(sphere, union_options(), "s").volume - sphere_exact);
  transform_mesh(sphere, Eigen::Matrix3d::Identity(), Eigen::Vector3d(1, 0, 0));
  const MeshReport report =
      analyze_mesh(mesh_fixtures::joined(box_mesh({2, 2, 2}), sphere), union_options(), "s.stl");
  const double hemisphere = 0.5 * sphere_exact;
  EXPECT_NEAR(report.volume, 8.0 + hemisphere, 0.5 * tessellation + 1e-12);
  const double centre_x = hemisphere * (1.0 + 3.0 * r / 8.0) / (8.0 + hemisphere);
  EXPECT_NEAR(report.mass_properties.center_of_mass.x(), centre_x, tessellation);
  EXPECT_NEAR(report.mass_properties.center_of_mass.y(), 0.0, 1e-12);
  EXPECT_NEAR(report.mass_properties.center_of_mass.z(), 0.0, 1e-12);
  // The shared volume is the half of the polyhedral sphere inside the box.
  EXPECT_NEAR(report.shared_volume, hemisphere, 0.5 * tessellation + 1e-12);
  // Inclusion-exclusion with the polyhedral sphere: the sum minus the shared volume, exactly.
  MassOptions sum = union_options();
  sum.overlap = OverlapMode::kSum;
  const MeshReport summed =
      analyze_mesh(mesh_fixtures::joined(box_mesh({2, 2, 2}), sphere), sum, "s.stl");
  EXPECT_NEAR(report.volume, summed.volume - report.shared_volume, 1e-12 * summed.volume);
}

TEST(PartUnion, ADuplicatedPartIsOnePart) {
  const TriangleMesh box = union_box({0, 0, 0}, {3, 2, 1});
  const MeshReport once = analyze_mesh(box, union_options(), "once.stl");
  for (const TriangleMesh& mesh : {mesh_fixtures::joined(box, box),
                                   mesh_fixtures::reversed(mesh_fixtures::joined(box, box))}) {
    const MeshReport twice = analyze_mesh(mesh, union_options(), "twice.stl");
    EXPECT_NEAR(twice.volume, 6.0, 1e-12 * 6.0);
    EXPECT_LE((twice.mass_properties.center_of_mass - once.mass_properties.center_of_mass).norm(),
              1e-12);
    expect_matrix_near(twice.mass_properties.inertia, once.mass_properties.inertia, 1e-12);
    EXPECT_NEAR(twice.shared_volume, 6.0, 1e-12 * 6.0);
    EXPECT_THAT(twice.warnings, Contains(AllOf(HasSubstr("is taken once (--overlap union)"),
                                               HasSubstr("counted once, is 6 m^3"))));
  }
}

TEST(PartUnion, ANestedPartIsInsideTheUnion) {
  const TriangleMesh mesh =
      mesh_fixtures::joined(union_box({0, 0, 0}, {4, 3, 2}), union_box({1, 1, 0.5}, {3, 2, 1.5}));
  const MeshReport report = analyze_mesh(mesh, union_options(), "nested.stl");
  EXPECT_NEAR(report.volume, 24.0, 1e-12 * 24.0);
  EXPECT_NEAR(report.shared_volume, 2.0, 1e-12 * 24.0);
  const BoxMoments outer = box_moments_about_origin({0, 0, 0}, {4, 3, 2});
  const Eigen::Vector3d centre(2.0, 1.5, 1.0);
  expect_matrix_near(report.mass_properties.inertia,
                     outer.inertia - 24.0 * (centre.squaredNorm() * Eigen::Matrix3d::Identity() -
                                             centre * centre.transpose()),
                     1e-12);
}

TEST(PartUnion, ACavityStaysACavityBesideAUnion) {
  // A box with a cavity, and a second box crossing its corner away from the cavity.
  const TriangleMesh hollow = mesh_fixtures::joined(
      union_box({0, 0, 0}, {4, 4, 4}), mesh_fixtures::reversed(union_box({1, 1, 1}, {2, 2, 2})));
  const TriangleMesh mesh = mesh_fixtures::joined(hollow, union_box({3, 3, 3}, {5, 5, 5}));
  const MeshReport report = analyze_mesh(mesh, union_options(), "hollow.stl");
  EXPECT_EQ(report.cavities, 1u);
  EXPECT_NEAR(report.volume, 64.0 - 1.0 + 8.0 - 1.0, 1e-12 * 70.0);
  EXPECT_NEAR(report.shared_volume, 1.0, 1e-12 * 70.0);
}

}  // namespace
}  // namespace tumble::engine
