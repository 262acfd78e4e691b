// Tests of the exact solids (engine/geometry/solids.hpp): unions of overlapping parts against
// the solid they span and against closed forms, convex hulls against solids known to be convex.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "engine/geometry/mesh_topology.hpp"
#include "engine/geometry/primitive_meshes.hpp"
#include "engine/geometry/solids.hpp"
#include "engine/mass/mass_properties.hpp"
#include "support/input_error.hpp"

namespace tumble::engine {
namespace {

using ::testing::HasSubstr;

/// A box of `size` with its low corner at `low`.
TriangleMesh placed_box(const Eigen::Vector3d& size, const Eigen::Vector3d& low) {
  TriangleMesh box = box_mesh(size);
  transform_mesh(box, Eigen::Matrix3d::Identity(), low + 0.5 * size);
  return box;
}

/// The union of every part of `parts` joined into one mesh.
TriangleMesh union_of(const std::vector<TriangleMesh>& parts) {
  TriangleMesh mesh;
  std::vector<std::uint32_t> triangle_part;
  std::vector<std::uint32_t> all;
  for (std::uint32_t i = 0; i < parts.size(); ++i) {
    append_mesh(mesh, parts[i]);
    triangle_part.resize(mesh.triangles.size(), i);
    all.push_back(i);
  }
  return union_of_parts(mesh, triangle_part, all);
}

MassProperties solid(const TriangleMesh& mesh) {
  const MomentIntegrals integrals = solid_integrals(mesh, Eigen::Vector3d::Zero());
  return mass_properties(integrals, Eigen::Vector3d::Zero(), 1.0);
}

double volume_of(const TriangleMesh& mesh) {
  return solid_integrals(mesh, Eigen::Vector3d::Zero()).measure;
}

TEST(SolidUnion, TwoBoxesSharingASlabAreTheBoxTheySpan) {
  const TriangleMesh merged =
      union_of({placed_box({2, 1, 1}, {0, 0, 0}), placed_box({2, 1, 1}, {1, 0, 0})});
  const MassProperties got = solid(merged);
  const MassProperties span = solid(placed_box({3, 1, 1}, {0, 0, 0}));
  EXPECT_NEAR(got.mass, 3.0, 1e-14);
  EXPECT_TRUE(got.center_of_mass.isApprox(span.center_of_mass, 1e-14));
  EXPECT_TRUE(got.inertia.isApprox(span.inertia, 1e-13)) << got.inertia << "\n" << span.inertia;
  // One closed surface, consistently wound.
  const Topology topology = analyze_topology(merged);
  EXPECT_TRUE(topology.closed());
  EXPECT_EQ(topology.parts, 1u);
}

TEST(SolidUnion, APartInsideAnotherAddsNothing) {
  const TriangleMesh merged =
      union_of({placed_box({4, 4, 4}, {0, 0, 0}), placed_box({1, 1, 1}, {1, 1, 1})});
  EXPECT_NEAR(volume_of(merged), 64.0, 1e-12);
}

TEST(SolidUnion, DisjointPartsKeepBothVolumes) {
  const TriangleMesh merged =
      union_of({placed_box({1, 1, 1}, {0, 0, 0}), placed_box({1, 2, 1}, {5, 0, 0})});
  EXPECT_NEAR(volume_of(merged), 3.0, 1e-14);
}

TEST(SolidUnion, TheSameBoxTwiceIsOneBox) {
  const TriangleMesh merged =
      union_of({placed_box({1, 2, 3}, {0, 0, 0}), placed_box({1, 2, 3}, {0, 0, 0})});
  EXPECT_NEAR(volume_of(merged), 6.0, 1e-13);
}

TEST(SolidUnion, ASphereThroughABoxFaceAddsTheHemisphereOutsideIt) {
  // A sphere centred on the face x = 1 of the box [-1, 1]^3: by the tessellation's symmetry
  // under x -> 2 - x, exactly half the polyhedral sphere lies outside the box. Its centre of
  // mass and inertia approach the hemisphere's closed forms as the tessellation refines.
  const double r = 0.5;
  for (const int segments : {32, 64}) {
    TriangleMesh sphere = uv_sphere_mesh(r, segments, segments / 2);
    const double sphere_volume = volume_of(sphere);
    transform_mesh(sphere, Eigen::Matrix3d::Identity(), Eigen::Vector3d(1, 0, 0));
    const TriangleMesh merged = union_of({box_mesh({2, 2, 2}), sphere});
    EXPECT_NEAR(volume_of(merged), 8.0 + 0.5 * sphere_volume, 1e-12) << segments;
    const MassProperties got = solid(merged);
    const double hemisphere = 2.0 / 3.0 * std::numbers::pi * r * r * r;
    const double x_hemisphere = 1.0 + 3.0 * r / 8.0;
    const double expected_x = hemisphere * x_hemisphere / (8.0 + hemisphere);
    EXPECT_NEAR(got.center_of_mass.x(), expected_x, segments == 32 ? 2e-3 : 5e-4) << segments;
  }
}

TEST(ConvexHull, OfACubesCornersAndInsidePointsIsTheCube) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> inside(0.05, 0.95);
  const Eigen::Matrix3d turn =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  std::vector<Eigen::Vector3d> points;
  for (const TriangleMesh& box = placed_box({1, 1, 1}, {0, 0, 0}); const auto& p : box.positions) {
    points.push_back(turn * p);
  }
  for (int i = 0; i < 500; ++i)
    points.push_back(turn * Eigen::Vector3d(inside(random), inside(random), inside(random)));
  const TriangleMesh hull = convex_hull_mesh(points, "cloud");
  EXPECT_NEAR(volume_of(hull), 1.0, 1e-14);
  EXPECT_TRUE(analyze_topology(hull).closed());
  EXPECT_EQ(hull.positions.size(), 8u);
}

TEST(ConvexHull, OfAConcaveSolidFillsItsDent) {
  // An L-shaped prism: its hull adds the triangular prism between the two arms.
  const std::vector<Eigen::Vector2d> outline{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  const TriangleMesh l_shape = extrude_polygon(outline, 0.0, 1.0);
  EXPECT_NEAR(volume_of(l_shape), 3.0, 1e-14);
  EXPECT_NEAR(volume_of(convex_hull_mesh(l_shape.positions, "L")), 3.5, 1e-14);
}

TEST(ConvexHull, PointsInOnePlaneHaveNoHull) {
  const std::vector<Eigen::Vector3d> flat{
      {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0.5, 0.2, 0}};
  EXPECT_THAT(testing::input_error_of([&] { convex_hull_mesh(flat, "plate.stl"); }),
              HasSubstr("plate.stl: its points lie in one plane"));
  EXPECT_THAT(testing::input_error_of([&] {
                convex_hull_mesh({{0, 0, 0}, {1, 0, 0}}, "x");
              }),
              HasSubstr("x: its points lie in one plane (or on one line)"));
}

}  // namespace
}  // namespace tumble::engine
