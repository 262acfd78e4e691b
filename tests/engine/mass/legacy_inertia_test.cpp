// The legacy method (MuJoCo 2.2.2's mesh inertia approximation). MuJoCo itself is its oracle
// in tests/app/robot/mjcf_legacy_mujoco_test.cpp; here: a box is exact, a ball is its box of
// equal inertia (closed form from exact's second moment), an L-prism gets 3.41565 m^3 (as
// MuJoCo 2.2.2 compiles it) against exact's 3, meshes exact refuses are taken, and the note
// says how far exact is.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "engine/geometry/primitive_meshes.hpp"
#include "engine/mass/mesh_analysis.hpp"
#include "inertia_expectations.hpp"
#include "support/input_error.hpp"
#include "support/l_prism.hpp"

namespace tumble::engine {
namespace {

using testing::expect_inertia_near;
using testing::expect_vector_near;
using ::testing::HasSubstr;
using testing::kExact;

MeshReport legacy_report(const TriangleMesh& mesh, double density = 2.0) {
  MassOptions options;
  options.inertia = InertiaMethod::legacy;
  options.density = density;
  return analyze_mesh(mesh, options, "legacy.stl");
}

TEST(LegacyInertia, ConvexBoxIsTheExactSolid) {
  // Sides and offset in powers of two: the vertices are floats as they are.
  TriangleMesh box = box_mesh({0.5, 1.0, 2.0});
  for (Eigen::Vector3d& p : box.positions) p += Eigen::Vector3d(0.25, -0.5, 1.0);
  const MeshReport legacy = legacy_report(box);
  EXPECT_EQ(legacy.method, InertiaMethod::legacy);
  const double m = 2.0 * 0.5 * 1.0 * 2.0;
  EXPECT_NEAR(legacy.mass_properties.mass, m, kExact * m);
  // MuJoCo sums each triangle's centroid in single precision (a third is no float): 1.5e-8.
  expect_vector_near(legacy.mass_properties.center_of_mass, {0.25, -0.5, 1.0}, 1e-7);
  const Eigen::Matrix3d expected =
      Eigen::Vector3d(m * (1.0 + 4.0) / 12, m * (0.25 + 4.0) / 12, m * (0.25 + 1.0) / 12)
          .asDiagonal();
  expect_inertia_near(legacy.mass_properties.inertia, expected);
  ASSERT_TRUE(legacy.enclosed_volume);
  EXPECT_NEAR(*legacy.enclosed_volume, 1.0, kExact);
  ASSERT_FALSE(legacy.warnings.empty());
  EXPECT_THAT(legacy.warnings.back(),
              HasSubstr("its volume equals the solid the mesh encloses (1 m^3, the exact "
                        "method's: a box)"));
}

TEST(LegacyInertia, ConvexBallIsItsBoxOfEqualInertia) {
  // Not a box: the mass is that of the box of equal inertia. The exact solid's second moment
  // C = c 1 (isotropic: icosahedral symmetry), c = I_exact / (2 rho), gives half sizes
  // sqrt(3c/V) and a volume 8 (3c/V)^(3/2); for a true sphere 8 (3/5)^(3/2) R^3, 11.2% less
  // than 4/3 pi R^3. Vertices off the grid of floats: MuJoCo's single precision costs 1e-7.
  TriangleMesh ball = icosphere_mesh(0.3, 2);
  for (Eigen::Vector3d& p : ball.positions) p += Eigen::Vector3d(0.1, 0.2, -0.3);
  MassOptions exact_options;
  exact_options.density = 2.0;
  const MeshReport exact = analyze_mesh(ball, exact_options, "ball.stl");
  const MeshReport legacy = legacy_report(ball);
  const double c = exact.mass_properties.inertia(0, 0) / (2 * 2.0);
  const double box_volume = 8 * std::pow(3 * c / exact.volume, 1.5);
  EXPECT_NEAR(legacy.volume, box_volume, 1e-6 * box_volume);
  EXPECT_NEAR(legacy.mass_properties.mass, 2.0 * box_volume, 1e-6 * 2.0 * box_volume);
  EXPECT_NEAR(legacy.volume / exact.volume, 8 * std::pow(0.6, 1.5) / (4 * std::numbers::pi / 3),
              0.01);
  expect_vector_near(legacy.mass_properties.center_of_mass, exact.mass_properties.center_of_mass,
                     1e-7);
  // The same distribution, scaled by the mass.
  expect_inertia_near(legacy.mass_properties.inertia,
                      exact.mass_properties.inertia * (legacy.volume / exact.volume), 1e-6);
  EXPECT_THAT(legacy.warnings.back(), HasSubstr("% less than the solid the mesh encloses"));
}

TEST(LegacyInertia, LPrismCountsTheFoldTwiceAndSaysHowFarExactIs) {
  const MeshReport legacy = legacy_report(tumble::testing::l_prism(), 1.0);
  // MuJoCo 2.2.2 compiles this mesh to a body_mass of 3.41565 at density 1.
  EXPECT_NEAR(legacy.mass_properties.mass, 3.41565, 1e-5);
  EXPECT_NEAR(legacy.volume, legacy.mass_properties.mass, kExact);
  ASSERT_TRUE(legacy.enclosed_volume);
  EXPECT_NEAR(*legacy.enclosed_volume, 3.0, kExact);
  ASSERT_FALSE(legacy.warnings.empty());
  EXPECT_THAT(legacy.warnings.back(),
              HasSubstr("legacy is MuJoCo 2.2.2's approximation (the box of equal inertia, from "
                        "absolute tetrahedron volumes about the mesh's centre): its volume "
                        "(3.41565 m^3) is 13.855% more than the solid the mesh encloses (3 m^3, "
                        "the exact method's)"));
}

TEST(LegacyInertia, TakesAnOpenMeshAndAGivenMass) {
  TriangleMesh open = box_mesh(Eigen::Vector3d::Constant(1.0));
  open.triangles.pop_back();
  open.triangles.pop_back();
  MassOptions options;
  options.inertia = InertiaMethod::legacy;
  options.mass = 4.0;
  const MeshReport report = analyze_mesh(open, options, "open.stl");
  EXPECT_EQ(report.method, InertiaMethod::legacy);
  EXPECT_NEAR(report.mass_properties.mass, 4.0, kExact);
  EXPECT_NEAR(report.density, 4.0 / report.volume, kExact);
  EXPECT_FALSE(report.enclosed_volume);
  EXPECT_THAT(report.warnings.back(),
              HasSubstr("exact refuses this mesh, so it cannot be compared with the enclosed "
                        "solid"));
}

TEST(LegacyInertia, FlatMeshIsRefused) {
  const TriangleMesh plate{{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 3}}};
  MassOptions options;
  options.inertia = InertiaMethod::legacy;
  EXPECT_THAT(tumble::testing::input_error_of([&] { analyze_mesh(plate, options, "plate.stl"); }),
              HasSubstr("plate.stl: spans no volume (all its faces lie in one plane)"));
}

}  // namespace
}  // namespace tumble::engine
