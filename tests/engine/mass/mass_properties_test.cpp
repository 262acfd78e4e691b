// Mass properties against independent oracles: closed forms of polyhedra (exact to rounding),
// O(h^2) convergence of tessellated curved solids, an exact-rational reference, and the
// invariances a rigid body's mass properties must have.
#include "engine/mass/mass_properties.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "engine/geometry/primitive_meshes.hpp"
#include "engine/mass/mesh_analysis.hpp"
#include "inertia_expectations.hpp"
#include "rational_reference.hpp"

namespace tumble::engine {
namespace {

using std::numbers::pi;
using ::testing::HasSubstr;

using testing::expect_inertia_near;
using testing::expect_vector_near;
using testing::kExact;
using testing::largest_moment;

/// The full pipeline at a given density (all checks on).
MeshReport analyze(const TriangleMesh& mesh, double density = 1000.0) {
  MassOptions options;
  options.density = density;
  return analyze_mesh(mesh, options, "test mesh");
}

Eigen::Matrix3d rotation(double angle, const Eigen::Vector3d& axis) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

/// An irregular closed polyhedron: a box with every corner moved independently (the quads are
/// no longer planar, the triangles are what counts), turned and moved off the axes.
TriangleMesh irregular_hexahedron() {
  TriangleMesh mesh = box_mesh({1.3, 0.7, 2.1});
  std::mt19937_64 rng(1234);
  std::uniform_real_distribution<double> jitter(-0.15, 0.15);
  for (Eigen::Vector3d& p : mesh.positions)
    p += Eigen::Vector3d(jitter(rng), jitter(rng), jitter(rng));
  transform_mesh(mesh, rotation(0.7, {1.0, -2.0, 0.5}), {0.31, -1.7, 2.9});
  return mesh;
}

/// A non-convex prism: an arrow-like outline extruded, then tilted.
TriangleMesh irregular_prism() {
  const std::vector<Eigen::Vector2d> outline = {{0.0, 0.0}, {2.1, 0.1},  {2.3, 1.7}, {1.1, 0.9},
                                                {0.6, 2.2}, {-0.4, 1.3}, {0.3, 0.8}};
  TriangleMesh mesh = extrude_polygon(outline, -0.35, 0.85);
  transform_mesh(mesh, rotation(1.1, {0.3, 1.0, -0.2}), {-4.2, 0.7, 1.9});
  return mesh;
}

// ---------------------------------------------------------------------------------------------
// Closed forms of polyhedra: the integral is exact, so the only error is rounding.

TEST(ClosedForm, Box) {
  const double a = 0.3, b = 1.7, c = 2.9, rho = 7.5;
  const MeshReport report = analyze(box_mesh({a, b, c}), rho);
  const MassProperties& mp = report.mass_properties;
  const double m = rho * a * b * c;
  EXPECT_NEAR(mp.mass, m, 1e-14 * m);
  EXPECT_NEAR(report.volume, a * b * c, 1e-14 * a * b * c);
  expect_vector_near(mp.center_of_mass, Eigen::Vector3d::Zero(), 1e-15);
  const Eigen::Vector3d diagonal(m * (b * b + c * c) / 12, m * (a * a + c * c) / 12,
                                 m * (a * a + b * b) / 12);
  expect_inertia_near(mp.inertia, diagonal.asDiagonal());
  expect_vector_near(report.principal.moments, {diagonal[2], diagonal[1], diagonal[0]},
                     kExact * diagonal.maxCoeff());
}

TEST(ClosedForm, TurnedAndMovedBox) {
  const double a = 1.1, b = 0.4, c = 0.9, rho = 2.0;
  const Eigen::Matrix3d turn = rotation(0.9, {1.0, 2.0, 3.0});
  const Eigen::Vector3d shift(5.5, -3.25, 0.125);
  TriangleMesh mesh = box_mesh({a, b, c});
  transform_mesh(mesh, turn, shift);
  const MassProperties mp = analyze(mesh, rho).mass_properties;
  const double m = rho * a * b * c;
  EXPECT_NEAR(mp.mass, m, 1e-13 * m);
  expect_vector_near(mp.center_of_mass, shift, 1e-14 * shift.norm());
  const Eigen::Vector3d diagonal(m * (b * b + c * c) / 12, m * (a * a + c * c) / 12,
                                 m * (a * a + b * b) / 12);
  expect_inertia_near(mp.inertia, turn * diagonal.asDiagonal() * turn.transpose());
}

TEST(ClosedForm, RegularTetrahedron) {
  // Alternate corners of a cube of half-side s: edge a = 2 sqrt(2) s, volume a^3 / (6 sqrt 2),
  // inertia m a^2 / 20 about every axis through the centroid.
  const double s = 0.75, rho = 3.0;
  const Eigen::Vector3d centre(1.5, -2.0, 0.25);
  TriangleMesh mesh = tetrahedron_mesh({Eigen::Vector3d(s, s, s), Eigen::Vector3d(s, -s, -s),
                                        Eigen::Vector3d(-s, s, -s), Eigen::Vector3d(-s, -s, s)});
  transform_mesh(mesh, rotation(0.4, {-1.0, 0.2, 0.7}), centre);
  const MeshReport report = analyze(mesh, rho);
  const double a = 2.0 * std::sqrt(2.0) * s;
  const double volume = a * a * a / (6.0 * std::sqrt(2.0));
  const double m = rho * volume;
  EXPECT_NEAR(report.volume, volume, 1e-14 * volume);
  expect_vector_near(report.mass_properties.center_of_mass, centre, 1e-14 * centre.norm());
  expect_inertia_near(report.mass_properties.inertia,
                      m * a * a / 20.0 * Eigen::Matrix3d::Identity());
}

TEST(ClosedForm, IrregularTetrahedron) {
  // Corner tetrahedron (0, a e1, b e2, c e3). From the Dirichlet integrals over the unit
  // simplex: V = abc/6, centroid (a, b, c)/4, int x^2 = V a^2/10, int xy = V ab/20, so about
  // the centroid int x'^2 = 3 V a^2 / 80 and int x'y' = -V ab / 80.
  const double a = 0.7, b = 1.9, c = 1.3, rho = 11.0;
  const double volume = a * b * c / 6.0;
  const double m = rho * volume;
  const Eigen::Vector3d centroid = Eigen::Vector3d(a, b, c) / 4.0;
  Eigen::Matrix3d second_about_centroid;
  second_about_centroid << 3 * a * a / 80, -a * b / 80, -a * c / 80,  //
      -a * b / 80, 3 * b * b / 80, -b * c / 80,                       //
      -a * c / 80, -b * c / 80, 3 * c * c / 80;
  second_about_centroid *= volume;
  const Eigen::Matrix3d inertia =
      rho * (second_about_centroid.trace() * Eigen::Matrix3d::Identity() - second_about_centroid);
  EXPECT_NEAR(inertia(0, 0), m * 3.0 * (b * b + c * c) / 80.0, 1e-15 * m);
  EXPECT_NEAR(inertia(0, 1), m * a * b / 80.0, 1e-15 * m);

  // Turned and moved: centroid R g + t, inertia R I R^T.
  const Eigen::Matrix3d turn = rotation(2.2, {0.5, -0.1, 1.0});
  const Eigen::Vector3d shift(-0.6, 2.4, 1.05);
  TriangleMesh mesh = tetrahedron_mesh({Eigen::Vector3d::Zero(), Eigen::Vector3d(a, 0, 0),
                                        Eigen::Vector3d(0, b, 0), Eigen::Vector3d(0, 0, c)});
  transform_mesh(mesh, turn, shift);
  const MeshReport report = analyze(mesh, rho);
  EXPECT_NEAR(report.mass_properties.mass, m, 1e-14 * m);
  expect_vector_near(report.mass_properties.center_of_mass, turn * centroid + shift, 1e-14 * 3.0);
  expect_inertia_near(report.mass_properties.inertia, turn * inertia * turn.transpose());
}

TEST(ClosedForm, RegularPolygonPrismIsExact) {
  // An N-gon cylinder is itself a polyhedron: V = N/2 r^2 sin(2 pi/N) h and, for the N-gon
  // inscribed in radius r, Izz/m = r^2 (1 + 2 cos^2(pi/N)) / 6 exactly.
  const double r = 0.8, h = 1.7;
  for (const int n : {3, 5, 12, 40}) {
    const MeshReport report = analyze(cylinder_mesh(r, h, n), 1.0);
    const double volume = 0.5 * n * r * r * std::sin(2.0 * pi / n) * h;
    EXPECT_NEAR(report.volume, volume, 1e-14 * volume) << n;
    const double c = std::cos(pi / n);
    const double izz = report.mass_properties.mass * r * r * (1.0 + 2.0 * c * c) / 6.0;
    EXPECT_NEAR(report.mass_properties.inertia(2, 2), izz, kExact * izz) << n;
  }
}

// ---------------------------------------------------------------------------------------------
// Curved solids: tessellations converge to the closed form as O(h^2).

/// Relative errors of a few quantities of one tessellation.
using Errors = std::vector<double>;

/// Observed convergence orders log2(e_N / e_2N) of each quantity over a doubling sweep.
void expect_second_order(const std::vector<int>& resolutions, const std::vector<Errors>& errors,
                         const std::vector<std::string>& names, double final_bound) {
  ASSERT_EQ(resolutions.size(), errors.size());
  for (std::size_t q = 0; q < names.size(); ++q) {
    for (std::size_t k = 0; k + 1 < errors.size(); ++k) {
      ASSERT_EQ(resolutions[k + 1], 2 * resolutions[k]);
      const double order = std::log2(errors[k][q] / errors[k + 1][q]);
      EXPECT_GE(order, 1.8) << names[q] << " N=" << resolutions[k] << ": errors " << errors[k][q]
                            << " -> " << errors[k + 1][q];
      EXPECT_LE(order, 2.2) << names[q] << " N=" << resolutions[k] << ": errors " << errors[k][q]
                            << " -> " << errors[k + 1][q];
    }
    EXPECT_LT(errors.back()[q], final_bound) << names[q];
  }
}

double relative_error(double actual, double expected) {
  return std::abs(actual - expected) / std::abs(expected);
}

const std::vector<int> kSweep = {16, 32, 64, 128};

TEST(Convergence, UvSphere) {
  const double r = 1.3;
  std::vector<Errors> errors;
  for (const int n : kSweep) {
    const MeshReport report = analyze(uv_sphere_mesh(r, n, n / 2), 1.0);
    const MassProperties& mp = report.mass_properties;
    const double i_over_m = 0.4 * r * r;
    errors.push_back({relative_error(report.volume, 4.0 / 3.0 * pi * r * r * r),
                      relative_error(mp.inertia(0, 0) / mp.mass, i_over_m),
                      relative_error(mp.inertia(2, 2) / mp.mass, i_over_m)});
    // Symmetric tessellation: centred, no products of inertia.
    expect_vector_near(mp.center_of_mass, Eigen::Vector3d::Zero(), 1e-14);
    EXPECT_NEAR(mp.inertia(0, 1), 0.0, kExact * mp.inertia(2, 2));
    EXPECT_NEAR(mp.inertia(1, 2), 0.0, kExact * mp.inertia(2, 2));
  }
  expect_second_order(kSweep, errors, {"volume", "Ixx/m", "Izz/m"}, 2e-3);
}

TEST(Convergence, Cylinder) {
  const double r = 0.6, h = 2.3;
  std::vector<Errors> errors;
  for (const int n : kSweep) {
    const MeshReport report = analyze(cylinder_mesh(r, h, n), 1.0);
    const MassProperties& mp = report.mass_properties;
    errors.push_back({relative_error(report.volume, pi * r * r * h),
                      relative_error(mp.inertia(2, 2) / mp.mass, r * r / 2.0),
                      relative_error(mp.inertia(0, 0) / mp.mass, (3.0 * r * r + h * h) / 12.0),
                      relative_error(mp.inertia(1, 1) / mp.mass, (3.0 * r * r + h * h) / 12.0)});
    // About 6.6 / N^2 for the axial moment (engine/PHYSICS.md §8).
    EXPECT_NEAR(errors.back()[1] * n * n, 2.0 * pi * pi / 3.0, 0.1) << n;
  }
  expect_second_order(kSweep, errors, {"volume", "Izz/m", "Ixx/m", "Iyy/m"}, 1e-3);
}

TEST(Convergence, ConeAboutItsCentreOfMass) {
  const double r = 0.9, h = 1.6;
  std::vector<Errors> errors;
  for (const int n : kSweep) {
    const MeshReport report = analyze(cone_mesh(r, h, n), 1.0);
    const MassProperties& mp = report.mass_properties;
    // A pyramid's centroid is a quarter of the way up for any base.
    expect_vector_near(mp.center_of_mass, {0.0, 0.0, h / 4.0}, 1e-14);
    errors.push_back(
        {relative_error(report.volume, pi * r * r * h / 3.0),
         relative_error(mp.inertia(2, 2) / mp.mass, 0.3 * r * r),
         relative_error(mp.inertia(0, 0) / mp.mass, 3.0 * r * r / 20.0 + 3.0 * h * h / 80.0),
         relative_error(mp.inertia(1, 1) / mp.mass, 3.0 * r * r / 20.0 + 3.0 * h * h / 80.0)});
  }
  expect_second_order(kSweep, errors, {"volume", "Izz/m", "Ixx/m", "Iyy/m"}, 1e-3);
}

TEST(Convergence, Torus) {
  const double major = 1.5, minor = 0.4;
  std::vector<Errors> errors;
  for (const int n : kSweep) {
    const MeshReport report = analyze(torus_mesh(major, minor, n, n), 1.0);
    const MassProperties& mp = report.mass_properties;
    const double a2 = minor * minor, r2 = major * major;
    errors.push_back({relative_error(report.volume, 2.0 * pi * pi * major * a2),
                      relative_error(mp.inertia(2, 2) / mp.mass, r2 + 0.75 * a2),
                      relative_error(mp.inertia(0, 0) / mp.mass, r2 / 2.0 + 5.0 * a2 / 8.0),
                      relative_error(mp.inertia(1, 1) / mp.mass, r2 / 2.0 + 5.0 * a2 / 8.0)});
    expect_vector_near(mp.center_of_mass, Eigen::Vector3d::Zero(), 1e-13);
  }
  expect_second_order(kSweep, errors, {"volume", "Izz/m", "Ixx/m", "Iyy/m"}, 1e-3);
}

// ---------------------------------------------------------------------------------------------
// Exact rational reference.

/// Compares the pipeline with the exact-rational oracle on the same doubles.
void expect_matches_rational_reference(const TriangleMesh& mesh, double density) {
  const rational_reference::ReferenceMassProperties exact =
      rational_reference::rational_mass_properties(mesh, density);
  const MeshReport report = analyze(mesh, density);
  const MassProperties& mp = report.mass_properties;
  EXPECT_NEAR(report.volume, exact.volume, 1e-13 * exact.volume);
  EXPECT_NEAR(mp.mass, exact.mass, 1e-13 * exact.mass);
  // The centre of mass to rounding of its own magnitude plus a tiny fraction of the size.
  const double size = (report.bounds_max - report.bounds_min).norm();
  expect_vector_near(mp.center_of_mass, exact.center_of_mass,
                     4e-16 * exact.center_of_mass.norm() + kExact * size);
  expect_inertia_near(mp.inertia, exact.inertia);
}

TEST(RationalReference, OracleIsExactOnTheUnitCube) {
  // The oracle itself: the cube [0, 1]^3 has V = 1, int x = 1/2, int x^2 = 1/3, int xy = 1/4.
  TriangleMesh cube = box_mesh({1.0, 1.0, 1.0});
  transform_mesh(cube, Eigen::Matrix3d::Identity(), {0.5, 0.5, 0.5});
  const rational_reference::RationalIntegrals sums =
      rational_reference::rational_solid_integrals(cube);
  EXPECT_EQ(sums.volume, 1);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(sums.first[i], mpq_class(1, 2));
    for (std::size_t j = 0; j < 3; ++j) {
      EXPECT_EQ(sums.second[i][j], i == j ? mpq_class(1, 3) : mpq_class(1, 4)) << i << j;
    }
  }
  const rational_reference::ReferenceMassProperties mp =
      rational_reference::rational_mass_properties(cube, 6.0);
  EXPECT_EQ(mp.inertia, Eigen::Matrix3d::Identity());  // 6 (1/12 + 1/12)
}

TEST(RationalReference, IrregularHexahedron) {
  expect_matches_rational_reference(irregular_hexahedron(), 1234.5);
}

TEST(RationalReference, NonConvexPrism) {
  expect_matches_rational_reference(irregular_prism(), 0.37);
}

TEST(RationalReference, OffCentreIcosphere) {
  TriangleMesh mesh = icosphere_mesh(0.9, 2);
  transform_mesh(mesh, Eigen::Vector3d(1.0, 0.6, 0.3).asDiagonal(), {3.3, -2.1, 0.7});
  expect_matches_rational_reference(mesh, 1000.0);
}

class FarFromOrigin : public ::testing::TestWithParam<double> {};

TEST_P(FarFromOrigin, BoxMatchesRationalReference) {
  // A turned box whose centre is `distance` from the origin; the rounded coordinates define
  // the polyhedron both sides integrate.
  const double distance = GetParam();
  TriangleMesh mesh = box_mesh({1.3, 0.7, 2.1});
  const Eigen::Vector3d centre = distance * Eigen::Vector3d(2.0, -1.0, 2.0) / 3.0;
  transform_mesh(mesh, rotation(0.6, {1.0, 1.0, -0.4}), centre);
  expect_matches_rational_reference(mesh, 800.0);

  // Teeth: integrating about the world origin in double precision misses the tolerance here,
  // so the test above would notice an engine that did that.
  const rational_reference::ReferenceMassProperties exact =
      rational_reference::rational_mass_properties(mesh, 800.0);
  const MassProperties naive = mass_properties(solid_integrals(mesh, Eigen::Vector3d::Zero()),
                                               Eigen::Vector3d::Zero(), 800.0);
  EXPECT_GT((naive.inertia - exact.inertia).cwiseAbs().maxCoeff(),
            kExact * largest_moment(exact.inertia));
}

INSTANTIATE_TEST_SUITE_P(Distances, FarFromOrigin, ::testing::Values(1e5, 1e8));

// ---------------------------------------------------------------------------------------------
// Invariances.

TEST(Invariance, TranslationMovesOnlyTheCentreOfMass) {
  const TriangleMesh mesh = irregular_prism();
  const MassProperties base = analyze(mesh).mass_properties;
  const Eigen::Vector3d offset(13.25, -7.5, 2.0625);
  TriangleMesh moved = mesh;
  transform_mesh(moved, Eigen::Matrix3d::Identity(), offset);
  const MassProperties mp = analyze(moved).mass_properties;
  EXPECT_NEAR(mp.mass, base.mass, 1e-13 * base.mass);
  expect_vector_near(mp.center_of_mass, base.center_of_mass + offset, 1e-13 * offset.norm());
  expect_inertia_near(mp.inertia, base.inertia);

  // MassProperties::translated does the same.
  const MassProperties shifted = base.translated(offset);
  EXPECT_EQ(shifted.mass, base.mass);
  EXPECT_EQ(shifted.inertia, base.inertia);
  expect_vector_near(shifted.center_of_mass, mp.center_of_mass, 1e-13 * offset.norm());
}

TEST(Invariance, RotationTurnsTheTensor) {
  const TriangleMesh mesh = irregular_hexahedron();
  const MassProperties base = analyze(mesh).mass_properties;
  std::mt19937_64 rng(77);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 5; ++trial) {
    const Eigen::Matrix3d turn =
        Eigen::Quaterniond(normal(rng), normal(rng), normal(rng), normal(rng))
            .normalized()
            .toRotationMatrix();
    TriangleMesh turned = mesh;
    transform_mesh(turned, turn, Eigen::Vector3d::Zero());
    const MassProperties mp = analyze(turned).mass_properties;
    EXPECT_NEAR(mp.mass, base.mass, 1e-13 * base.mass);
    expect_vector_near(mp.center_of_mass, turn * base.center_of_mass, 1e-13);
    expect_inertia_near(mp.inertia, turn * base.inertia * turn.transpose());

    const MassProperties rotated = base.rotated(turn);
    expect_vector_near(rotated.center_of_mass, mp.center_of_mass, 1e-13);
    expect_inertia_near(rotated.inertia, mp.inertia);
  }
}

TEST(Invariance, InertiaAboutAPointIsTheParallelAxisShift) {
  // inertia_about(p) against integrating the second moment about p directly.
  const TriangleMesh mesh = irregular_hexahedron();
  const double rho = 3.5;
  const MassProperties mp = analyze(mesh, rho).mass_properties;
  for (const Eigen::Vector3d& point :
       {Eigen::Vector3d(0.0, 0.0, 0.0), Eigen::Vector3d(1.0, -2.0, 0.5),
        Eigen::Vector3d(0.31, -1.7, 2.9)}) {
    const Eigen::Matrix3d direct =
        inertia_from_second_moment(solid_integrals(mesh, point).second, rho);
    expect_inertia_near(mp.inertia_about(point), direct);
  }
  // About the centre of mass it is the inertia itself.
  EXPECT_EQ(mp.inertia_about(mp.center_of_mass), mp.inertia);
}

TEST(Invariance, UniformScaleAtFixedDensity) {
  const TriangleMesh mesh = irregular_prism();
  const MeshReport base = analyze(mesh, 700.0);
  for (const double s : {1e-3, 0.5, 2.5, 40.0}) {
    MassOptions options;
    options.density = 700.0;
    options.scale = Eigen::Vector3d::Constant(s);
    const MeshReport scaled = analyze_mesh(mesh, options, "scaled");
    const double s3 = s * s * s, s5 = s3 * s * s;
    EXPECT_NEAR(scaled.volume, s3 * base.volume, 1e-13 * s3 * base.volume) << s;
    EXPECT_NEAR(scaled.mass_properties.mass, s3 * base.mass_properties.mass,
                1e-13 * s3 * base.mass_properties.mass)
        << s;
    EXPECT_EQ(scaled.density, 700.0);
    expect_vector_near(scaled.mass_properties.center_of_mass,
                       s * base.mass_properties.center_of_mass,
                       1e-13 * s * base.mass_properties.center_of_mass.norm());
    expect_inertia_near(scaled.mass_properties.inertia, s5 * base.mass_properties.inertia);
    expect_vector_near(scaled.bounds_max, s * base.bounds_max, 1e-15 * s * base.bounds_max.norm());
  }
}

TEST(Invariance, WindingFlipGivesTheSameBodyAndSaysSo) {
  const TriangleMesh mesh = irregular_hexahedron();
  const MeshReport base = analyze(mesh);
  EXPECT_FALSE(base.flipped);
  EXPECT_THAT(base.warnings, ::testing::IsEmpty());

  TriangleMesh inverted = mesh;
  for (auto& t : inverted.triangles) std::swap(t[0], t[2]);
  const MeshReport report = analyze(inverted);
  EXPECT_TRUE(report.flipped);
  EXPECT_THAT(report.warnings, ::testing::ElementsAre(HasSubstr("flipped them all")));
  EXPECT_NEAR(report.volume, base.volume, 1e-14 * base.volume);
  expect_vector_near(report.mass_properties.center_of_mass, base.mass_properties.center_of_mass,
                     1e-14);
  expect_inertia_near(report.mass_properties.inertia, base.mass_properties.inertia);
}

TEST(Invariance, TriangleOrderAndCornerRotation) {
  const TriangleMesh mesh = irregular_prism();
  const MeshReport base = analyze(mesh);
  std::mt19937_64 rng(3);
  for (int trial = 0; trial < 5; ++trial) {
    TriangleMesh shuffled = mesh;
    std::shuffle(shuffled.triangles.begin(), shuffled.triangles.end(), rng);
    for (auto& t : shuffled.triangles) {
      std::rotate(t.begin(), t.begin() + static_cast<std::ptrdiff_t>(rng() % 3), t.end());
    }
    ASSERT_NE(shuffled.triangles, mesh.triangles);
    const MeshReport report = analyze(shuffled);
    EXPECT_FALSE(report.flipped);
    EXPECT_NEAR(report.volume, base.volume, 1e-14 * base.volume);
    expect_vector_near(report.mass_properties.center_of_mass, base.mass_properties.center_of_mass,
                       1e-13);
    expect_inertia_near(report.mass_properties.inertia, base.mass_properties.inertia);
  }
}

TEST(Invariance, UnweldedSoupEqualsWeldedMesh) {
  const TriangleMesh mesh = irregular_hexahedron();
  TriangleMesh soup;
  for (const auto& t : mesh.triangles) {
    const auto base = static_cast<std::uint32_t>(soup.positions.size());
    for (const std::uint32_t v : t) soup.positions.push_back(mesh.positions[v]);
    soup.triangles.push_back({base, base + 1, base + 2});
  }
  const MeshReport welded = analyze(mesh);
  const MeshReport report = analyze(soup);
  EXPECT_EQ(report.welded_vertices, soup.positions.size() - mesh.positions.size());
  EXPECT_EQ(report.vertices, mesh.positions.size());
  EXPECT_TRUE(report.watertight);
  EXPECT_NEAR(report.volume, welded.volume, kExact * welded.volume);
  expect_vector_near(report.mass_properties.center_of_mass, welded.mass_properties.center_of_mass,
                     1e-13);
  expect_inertia_near(report.mass_properties.inertia, welded.mass_properties.inertia);
}

TEST(MassOrDensity, GivenMassSetsDensityAndScalesInertia) {
  const TriangleMesh mesh = irregular_hexahedron();
  const MeshReport unit = analyze(mesh, 1.0);
  MassOptions options;
  options.mass = 42.0;
  const MeshReport report = analyze_mesh(mesh, options, "by mass");
  EXPECT_NEAR(report.mass_properties.mass, 42.0, 1e-13 * 42.0);
  EXPECT_NEAR(report.density, 42.0 / unit.volume, 1e-13 * report.density);
  expect_vector_near(report.mass_properties.center_of_mass, unit.mass_properties.center_of_mass,
                     1e-14);
  expect_inertia_near(report.mass_properties.inertia,
                      42.0 / unit.volume * unit.mass_properties.inertia);

  // The default density is water.
  const MeshReport water = analyze_mesh(mesh, MassOptions{}, "default");
  EXPECT_EQ(water.density, 1000.0);
  EXPECT_NEAR(water.mass_properties.mass, 1000.0 * unit.volume, 1e-13 * water.mass_properties.mass);
}

// ---------------------------------------------------------------------------------------------
// The building blocks.

TEST(SolidIntegrals, UnitCubeAboutACorner) {
  TriangleMesh cube = box_mesh({1.0, 1.0, 1.0});
  const MomentIntegrals about_corner = solid_integrals(cube, {-0.5, -0.5, -0.5});
  EXPECT_NEAR(about_corner.measure, 1.0, 1e-15);
  expect_vector_near(about_corner.first, Eigen::Vector3d::Constant(0.5), 1e-15);
  Eigen::Matrix3d expected = Eigen::Matrix3d::Constant(0.25);
  expected.diagonal().setConstant(1.0 / 3.0);
  EXPECT_LE((about_corner.second - expected).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(SurfaceIntegrals, UnitCubeSurface) {
  // Each face of the unit cube centred at the origin: area 1; int x^2 over the two x faces is
  // 2 * 1/4, over the four others 4 * 1/12: 5/6 in all. Products vanish by symmetry.
  const MomentIntegrals surface =
      surface_integrals(box_mesh({1.0, 1.0, 1.0}), Eigen::Vector3d::Zero());
  EXPECT_NEAR(surface.measure, 6.0, 1e-14);
  expect_vector_near(surface.first, Eigen::Vector3d::Zero(), 1e-15);
  EXPECT_LE((surface.second - 5.0 / 6.0 * Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(),
            1e-14);
}

TEST(MassPropertiesFromIntegrals, ReferencePointDoesNotMatter) {
  const TriangleMesh mesh = irregular_prism();
  const MassProperties a =
      mass_properties(solid_integrals(mesh, {-4.0, 0.5, 2.0}), {-4.0, 0.5, 2.0}, 2.0);
  const MassProperties b =
      mass_properties(solid_integrals(mesh, {-4.5, 1.0, 1.5}), {-4.5, 1.0, 1.5}, 2.0);
  EXPECT_NEAR(a.mass, b.mass, 1e-14 * a.mass);
  expect_vector_near(a.center_of_mass, b.center_of_mass, 1e-13);
  expect_inertia_near(a.inertia, b.inertia);
}

}  // namespace
}  // namespace tumble::engine
