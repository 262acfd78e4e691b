// Primitive shapes: closed-form mass properties against textbook values and against the
// engine's exact integrals of fine tessellations, whose error must shrink as O(1/n^2);
// validation of the dimensions (engine/PHYSICS.md §9).
#include "engine/mass/primitive_shapes.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "base/errors.hpp"
#include "inertia_expectations.hpp"
#include "support/input_error.hpp"

namespace tumble::engine {
namespace {

using testing::expect_inertia_near;
using testing::expect_vector_near;
using ::testing::HasSubstr;
using testing::kExact;
using tumble::testing::input_error_of;
constexpr double kPrimitiveDensity = 1250.0;

Eigen::Matrix3d diagonal(double a, double b, double c) {
  return Eigen::Vector3d(a, b, c).asDiagonal();
}

/// The mass properties of the shape's tessellation with `segments`, by the mesh integrals.
MassProperties mesh_properties(const Shape& shape, int segments) {
  const TriangleMesh mesh = tessellate(shape, segments);
  const Eigen::Vector3d reference = Eigen::Vector3d::Zero();
  return mass_properties(solid_integrals(mesh, reference), reference, kPrimitiveDensity);
}

/// The largest entry of the inertia's difference, relative to the exact largest moment.
double inertia_error(const MassProperties& actual, const MassProperties& exact) {
  return (actual.inertia - exact.inertia).cwiseAbs().maxCoeff() /
         exact.inertia.diagonal().maxCoeff();
}

/// Every shape kind once, with unequal dimensions.
std::vector<Shape> sample_shapes() {
  return {Box{{1.3, 0.7, 2.1}},        Sphere{0.45},  Cylinder{0.3, 1.7}, Capsule{0.25, 0.9},
          Ellipsoid{{0.6, 0.35, 1.1}}, Cone{0.5, 1.4}};
}

TEST(PrimitiveShapes, KindsAreSpelledAsInSceneFiles) {
  std::vector<std::string> kinds;
  for (const Shape& shape : sample_shapes()) kinds.emplace_back(shape_kind(shape));
  EXPECT_EQ(kinds, (std::vector<std::string>{"box", "sphere", "cylinder", "capsule", "ellipsoid",
                                             "cone"}));
}

TEST(PrimitiveShapes, BoxSphereCylinderEllipsoidConeMatchTheTextbookForms) {
  const double a = 1.3, b = 0.7, c = 2.1;
  const MassProperties box = mass_properties(Box{{a, b, c}}, kPrimitiveDensity);
  double m = kPrimitiveDensity * a * b * c;
  EXPECT_NEAR(box.mass, m, 1e-12 * m);
  expect_inertia_near(box.inertia,
                      m / 12.0 * diagonal(b * b + c * c, a * a + c * c, a * a + b * b));

  const double r = 0.45;
  const MassProperties sphere = mass_properties(Sphere{r}, kPrimitiveDensity);
  m = kPrimitiveDensity * 4.0 / 3.0 * std::numbers::pi * r * r * r;
  EXPECT_NEAR(sphere.mass, m, 1e-12 * m);
  expect_inertia_near(sphere.inertia, 0.4 * m * r * r * Eigen::Matrix3d::Identity());

  const double cr = 0.3, l = 1.7;
  const MassProperties cylinder = mass_properties(Cylinder{cr, l}, kPrimitiveDensity);
  m = kPrimitiveDensity * std::numbers::pi * cr * cr * l;
  EXPECT_NEAR(cylinder.mass, m, 1e-12 * m);
  const double across = m * (3.0 * cr * cr + l * l) / 12.0;
  expect_inertia_near(cylinder.inertia, diagonal(across, across, m * cr * cr / 2.0));

  const Eigen::Vector3d radii(0.6, 0.35, 1.1);
  const MassProperties ellipsoid = mass_properties(Ellipsoid{radii}, kPrimitiveDensity);
  m = kPrimitiveDensity * 4.0 / 3.0 * std::numbers::pi * radii.prod();
  EXPECT_NEAR(ellipsoid.mass, m, 1e-12 * m);
  const Eigen::Vector3d r2 = radii.cwiseAbs2();
  expect_inertia_near(ellipsoid.inertia,
                      m / 5.0 * diagonal(r2[1] + r2[2], r2[0] + r2[2], r2[0] + r2[1]));

  const double kr = 0.5, h = 1.4;
  const MassProperties cone = mass_properties(Cone{kr, h}, kPrimitiveDensity);
  m = kPrimitiveDensity * std::numbers::pi * kr * kr * h / 3.0;
  EXPECT_NEAR(cone.mass, m, 1e-12 * m);
  const double tilt = m * (3.0 * kr * kr / 20.0 + 3.0 * h * h / 80.0);
  expect_inertia_near(cone.inertia, diagonal(tilt, tilt, 0.3 * m * kr * kr));
  for (const MassProperties* p : {&box, &sphere, &cylinder, &ellipsoid, &cone}) {
    EXPECT_EQ(p->center_of_mass, Eigen::Vector3d::Zero());
  }
}

// The capsule assembled by hand: a cylinder and two hemispheres, each hemisphere's inertia
// about its own centre of mass (83/320 m r^2 across, 2/5 m r^2 about the axis) shifted by
// l/2 + 3r/8 to the middle.
TEST(PrimitiveShapes, CapsuleIsACylinderAndTwoShiftedHemispheres) {
  const double r = 0.25, l = 0.9;
  const double m_cylinder = kPrimitiveDensity * std::numbers::pi * r * r * l;
  const double m_half = kPrimitiveDensity * 2.0 / 3.0 * std::numbers::pi * r * r * r;
  const double shift = l / 2.0 + 3.0 * r / 8.0;
  const double across = m_cylinder * (3.0 * r * r + l * l) / 12.0 +
                        2.0 * (83.0 / 320.0 * m_half * r * r + m_half * shift * shift);
  const double axial = m_cylinder * r * r / 2.0 + 2.0 * (0.4 * m_half * r * r);

  const MassProperties capsule = mass_properties(Capsule{r, l}, kPrimitiveDensity);
  EXPECT_NEAR(capsule.mass, m_cylinder + 2.0 * m_half, 1e-12 * capsule.mass);
  expect_inertia_near(capsule.inertia, diagonal(across, across, axial));
  EXPECT_NEAR(volume(Capsule{r, l}),
              std::numbers::pi * r * r * l + 4.0 / 3.0 * std::numbers::pi * r * r * r, 1e-15);
}

TEST(PrimitiveShapes, LimitsAgreeBetweenShapes) {
  // A capsule with a vanishing cylinder is a sphere; a sphere is an ellipsoid; a cube is a box.
  const double r = 0.7;
  const MassProperties sphere = mass_properties(Sphere{r}, kPrimitiveDensity);
  const MassProperties short_capsule = mass_properties(Capsule{r, 1e-14}, kPrimitiveDensity);
  EXPECT_NEAR(short_capsule.mass, sphere.mass, 1e-12 * sphere.mass);
  expect_inertia_near(short_capsule.inertia, sphere.inertia);
  expect_inertia_near(
      mass_properties(Ellipsoid{Eigen::Vector3d::Constant(r)}, kPrimitiveDensity).inertia,
      sphere.inertia);
}

TEST(PrimitiveShapes, AGivenMassIsKeptExactlyAndScalesTheInertia) {
  for (const Shape& shape : sample_shapes()) {
    const MassProperties by_mass = mass_properties_of_mass(shape, 3.25);
    EXPECT_EQ(by_mass.mass, 3.25) << shape_kind(shape);
    const MassProperties by_density = mass_properties(shape, 3.25 / volume(shape));
    expect_inertia_near(by_mass.inertia, by_density.inertia);
    EXPECT_TRUE(by_mass.inertia.isDiagonal(0.0)) << shape_kind(shape);
  }
}

// The box's tessellation is the box: the mesh integrals agree to rounding.
TEST(PrimitiveShapes, BoxMatchesItsMeshExactly) {
  const Shape box = Box{{1.3, 0.7, 2.1}};
  const MassProperties exact = mass_properties(box, kPrimitiveDensity);
  const MassProperties mesh = mesh_properties(box, 4);
  EXPECT_NEAR(mesh.mass, exact.mass, 1e-12 * exact.mass);
  expect_vector_near(mesh.center_of_mass, Eigen::Vector3d::Zero(), 1e-15);
  expect_inertia_near(mesh.inertia, exact.inertia, kExact);
}

// Curved shapes: the inscribed tessellation's mass and inertia approach the closed form with an
// error that quarters as the segments (and the latitude bands with them) double.
TEST(PrimitiveShapes, TessellationsConvergeAtSecondOrderToTheClosedForms) {
  for (const Shape& shape : sample_shapes()) {
    if (std::holds_alternative<Box>(shape)) continue;
    SCOPED_TRACE(std::string(shape_kind(shape)));
    const MassProperties exact = mass_properties(shape, kPrimitiveDensity);
    std::vector<double> mass_errors, inertia_errors;
    for (int segments : {32, 64, 128, 256}) {
      const MassProperties mesh = mesh_properties(shape, segments);
      expect_vector_near(mesh.center_of_mass, Eigen::Vector3d::Zero(), 1e-12);
      EXPECT_LT(mesh.mass, exact.mass);  // inscribed
      mass_errors.push_back((exact.mass - mesh.mass) / exact.mass);
      inertia_errors.push_back(inertia_error(mesh, exact));
    }
    for (std::size_t k = 1; k < mass_errors.size(); ++k) {
      EXPECT_NEAR(mass_errors[k - 1] / mass_errors[k], 4.0, 0.25) << "step " << k;
      EXPECT_NEAR(inertia_errors[k - 1] / inertia_errors[k], 4.0, 0.3) << "step " << k;
    }
    // The constant of O(1/n^2) is modest: at 256 segments the meshes agree to 1e-3.
    EXPECT_LT(mass_errors.back(), 1e-3);
    EXPECT_LT(inertia_errors.back(), 1e-3);
  }
}

// The cylinder's N-gon prism has Izz / m = r^2 (2 + cos(2 pi / N)) / 6 exactly (§8).
TEST(PrimitiveShapes, CylinderMeshMatchesThePolygonFormula) {
  const double r = 0.3, l = 1.7;
  for (int n : {8, 64}) {
    const MassProperties mesh = mesh_properties(Cylinder{r, l}, n);
    const double expected = r * r * (2.0 + std::cos(2.0 * std::numbers::pi / n)) / 6.0;
    EXPECT_NEAR(mesh.inertia(2, 2) / mesh.mass, expected, 1e-13) << n;
  }
}

TEST(PrimitiveShapes, TheConeHasItsBaseAQuarterOfTheHeightBelowTheOrigin) {
  const TriangleMesh mesh = tessellate(Cone{0.5, 1.4}, 16);
  double low = 0.0, high = 0.0;
  for (const Eigen::Vector3d& p : mesh.positions) {
    low = std::min(low, p.z());
    high = std::max(high, p.z());
  }
  EXPECT_DOUBLE_EQ(low, -0.35);
  EXPECT_DOUBLE_EQ(high, 1.05);
  // Any pyramid's centroid is a quarter of the way up: the coarse mesh's too.
  expect_vector_near(mesh_properties(Cone{0.5, 1.4}, 5).center_of_mass, Eigen::Vector3d::Zero(),
                     1e-14);
}

TEST(PrimitiveShapes, TheCapsuleSpansItsCylinderAndBothCaps) {
  const TriangleMesh mesh = tessellate(Capsule{0.25, 0.9}, 24);
  double low = 0.0, high = 0.0, widest = 0.0;
  for (const Eigen::Vector3d& p : mesh.positions) {
    low = std::min(low, p.z());
    high = std::max(high, p.z());
    widest = std::max(widest, p.head<2>().norm());
  }
  EXPECT_DOUBLE_EQ(low, -0.7);
  EXPECT_DOUBLE_EQ(high, 0.7);
  EXPECT_NEAR(widest, 0.25, 1e-15);
}

TEST(PrimitiveShapes, BadDimensionsNameTheField) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  struct Case {
    Shape shape;
    std::string message;
  };
  const std::vector<Case> cases = {
      {Box{{1.0, 0.0, 1.0}}, "box size[1]: expected a positive finite number, got 0"},
      {Sphere{-2.0}, "sphere radius: expected a positive finite number, got -2"},
      {Cylinder{1.0, nan}, "cylinder length: expected a positive finite number, got nan"},
      {Capsule{inf, 1.0}, "capsule radius: expected a positive finite number, got inf"},
      {Ellipsoid{{1.0, 1.0, -0.5}}, "ellipsoid radii[2]: expected a positive finite number"},
      {Cone{1.0, -inf}, "cone height: expected a positive finite number, got -inf"},
      {Sphere{1e120}, "sphere: its volume (inf m^3) or moments of inertia are beyond the range"},
      {Box{{1e-120, 1e-120, 1e-120}}, "box: its volume (0 m^3)"},
  };
  for (const Case& c : cases) {
    EXPECT_THAT(input_error_of([&] { volume(c.shape); }), HasSubstr(c.message));
    EXPECT_THAT(input_error_of([&] { mass_properties(c.shape, 1.0); }), HasSubstr(c.message));
    EXPECT_THAT(input_error_of([&] { tessellate(c.shape, 16); }), HasSubstr(c.message));
  }
}

TEST(PrimitiveShapes, BadMatterAndSegmentsAreRefused) {
  const Shape sphere = Sphere{1.0};
  EXPECT_THAT(input_error_of([&] { mass_properties(sphere, -1.0); }),
              HasSubstr("density: expected a positive finite number, got -1"));
  EXPECT_THAT(input_error_of([&] { mass_properties_of_mass(sphere, 0.0); }),
              HasSubstr("mass: expected a positive finite number, got 0"));
  EXPECT_THAT(input_error_of([&] { mass_properties(sphere, 1e308); }),
              HasSubstr("sphere: the mass density * volume = inf kg"));
  EXPECT_THAT(input_error_of([&] { mass_properties_of_mass(Sphere{1e100}, 1e300); }),
              HasSubstr("sphere: its moments of inertia for a mass of 1e+300 kg are beyond"));
  EXPECT_THAT(input_error_of([&] { tessellate(sphere, 3); }),
              HasSubstr("tessellate: expected at least 4 segments, got 3"));
}

}  // namespace
}  // namespace tumble::engine
