// Every check of the `tumble inspect` pipeline: what it rejects (with which message), what it
// repairs (and says so), and that repairs leave the mass properties right.
#include "engine/mass/mesh_analysis.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "base/errors.hpp"
#include "engine/geometry/mesh_topology.hpp"
#include "engine/geometry/primitive_meshes.hpp"
#include "engine/mesh_fixtures.hpp"
#include "engine/overlap/part_overlap.hpp"
#include "inertia_expectations.hpp"
#include "rational_reference.hpp"
#include "support/input_error.hpp"

namespace tumble::engine {
namespace {

using ::testing::AllOf;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using ::testing::StartsWith;

using testing::expect_inertia_near;
using testing::expect_vector_near;
using testing::kExact;
using testing::largest_moment;

MassOptions with_density(double density) {
  MassOptions options;
  options.density = density;
  return options;
}

/// Box of edge lengths `size` centred at `centre`.
TriangleMesh box(const Eigen::Vector3d& size, const Eigen::Vector3d& centre) {
  TriangleMesh mesh = box_mesh(size);
  transform_mesh(mesh, Eigen::Matrix3d::Identity(), centre);
  return mesh;
}

using mesh_fixtures::joined;
using mesh_fixtures::reversed;

/// Box inertia about its centre, m (b^2 + c^2) / 12 etc.
Eigen::Matrix3d box_inertia(double density, const Eigen::Vector3d& size) {
  const double m = density * size.prod();
  const Eigen::Vector3d s2 = size.cwiseProduct(size);
  return (m / 12.0 * Eigen::Vector3d(s2.y() + s2.z(), s2.x() + s2.z(), s2.x() + s2.y()))
      .asDiagonal();
}

/// Parallel-axis shift of an inertia about the centre of mass to a point `d` away from it.
Eigen::Matrix3d shifted(const Eigen::Matrix3d& inertia, double mass, const Eigen::Vector3d& d) {
  return inertia + mass * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
}

/// The message of the InputError `analyze_mesh` throws (fails the test if it does not).
std::string error_of(const TriangleMesh& mesh, const MassOptions& options = {},
                     const std::string& source = "part.stl") {
  return tumble::testing::input_error_of([&] { analyze_mesh(mesh, options, source); }, "the mesh");
}

// ---------------------------------------------------------------------------------------------
// Rejected meshes.

TEST(MeshChecks, OpenSurfaceCountsBoundaryEdgesAndSuggestsShell) {
  TriangleMesh mesh = box_mesh({1.0, 2.0, 3.0});
  mesh.triangles.pop_back();  // one triangle missing: its three edges are boundary edges
  EXPECT_THAT(error_of(mesh), AllOf(StartsWith("part.stl: "), HasSubstr("open"),
                                    HasSubstr("3 boundary edges"), HasSubstr("--shell")));

  // A whole face missing: 4 boundary edges around the square hole.
  TriangleMesh lidless = box_mesh({1.0, 2.0, 3.0});
  lidless.triangles.resize(lidless.triangles.size() - 2);
  EXPECT_THAT(error_of(lidless), HasSubstr("(4 boundary edges)"));
}

TEST(MeshChecks, OneFlippedFaceIsInconsistentWinding) {
  TriangleMesh mesh = box_mesh({1.0, 2.0, 3.0});
  std::swap(mesh.triangles[5][1], mesh.triangles[5][2]);
  EXPECT_THAT(error_of(mesh), AllOf(StartsWith("part.stl: "), HasSubstr("inconsistent winding"),
                                    HasSubstr("3 edges used twice in the same direction")));
}

TEST(MeshChecks, EdgesOfThreeTrianglesAreNonManifoldNotInconsistentWinding) {
  // One face of the box again, reversed (a stray copy as some exporters leave): its three edges
  // are each used by three triangles, twice one way and once the other. That is no winding
  // error between two neighbours; it used to be called "inconsistent winding".
  TriangleMesh mesh = box_mesh({1.0, 2.0, 3.0});
  const auto copy = mesh.triangles[5];
  mesh.triangles.push_back({copy[0], copy[2], copy[1]});
  EXPECT_EQ(error_of(mesh),
            "part.stl: not a manifold: 3 edges shared by three or more triangles whose "
            "directions do not pair up (as many one way as the other), so the surface does not "
            "bound a volume");
}

TEST(MeshChecks, ClosedFlatSurfaceHasZeroVolume) {
  // A square with both sides: every edge used once each way, so closed, but flat.
  const TriangleMesh square{{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}},
                            {{0, 1, 2}, {0, 2, 3}, {0, 2, 1}, {0, 3, 2}}};
  EXPECT_THAT(error_of(square),
              AllOf(StartsWith("part.stl: "), HasSubstr("zero volume"), HasSubstr("--shell")));

  // The same flat square tilted and far away: still zero, whatever the rounding.
  TriangleMesh tilted = square;
  transform_mesh(tilted,
                 Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix(),
                 {1e3, -2e3, 5e2});
  EXPECT_THAT(error_of(tilted), HasSubstr("zero volume"));
}

TEST(MeshChecks, ThinButRealSolidIsNotZeroVolume) {
  // No absolute threshold: a 1 um thick plate of 1 m^2 is a solid.
  const Eigen::Vector3d size(1.0, 1.0, 1e-6);
  const MeshReport report = analyze_mesh(box_mesh(size), with_density(1.0), "plate");
  EXPECT_NEAR(report.volume, 1e-6, 1e-6 * kExact);
  expect_inertia_near(report.mass_properties.inertia, box_inertia(1.0, size));
}

TEST(MeshChecks, NonFiniteCoordinateNamesTheVertex) {
  for (const double bad :
       {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
        -std::numeric_limits<double>::infinity()}) {
    TriangleMesh mesh = box_mesh({1.0, 1.0, 1.0});
    mesh.positions[2].y() = bad;
    EXPECT_THAT(error_of(mesh),
                AllOf(StartsWith("part.stl: "), HasSubstr("vertex 3 has a non-finite coordinate")));
  }
  // Finite in the file, infinite once scaled.
  TriangleMesh huge = box_mesh({1.0, 1.0, 1.0});
  huge.positions[0].x() = 1e300;
  MassOptions options;
  options.scale = Eigen::Vector3d::Constant(1e10);
  EXPECT_THAT(error_of(huge, options), HasSubstr("vertex 1 has a non-finite coordinate"));
}

TEST(MeshChecks, EmptyMesh) {
  EXPECT_THAT(error_of(TriangleMesh{}), AllOf(StartsWith("part.stl: "), HasSubstr("no triangles")));
  const TriangleMesh only_points{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {}};
  EXPECT_THAT(error_of(only_points), HasSubstr("no triangles"));
}

TEST(MeshChecks, AllTrianglesDegenerate) {
  const TriangleMesh mesh{{{0, 0, 0}, {1, 0, 0}, {0, 0, 0}}, {{0, 1, 1}, {0, 1, 2}}};
  EXPECT_THAT(error_of(mesh), HasSubstr("all 2 triangles are degenerate"));
}

TEST(MeshChecks, BadOptions) {
  const TriangleMesh mesh = box_mesh({1.0, 1.0, 1.0});
  MassOptions negative_density;
  negative_density.density = -5.0;
  EXPECT_THAT(error_of(mesh, negative_density),
              AllOf(StartsWith("part.stl: "), HasSubstr("density must be a positive finite number"),
                    HasSubstr("-5")));

  MassOptions nan_density;
  nan_density.density = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT(error_of(mesh, nan_density), HasSubstr("density must be a positive finite number"));

  MassOptions zero_scale;
  zero_scale.scale = Eigen::Vector3d::Zero();
  EXPECT_THAT(error_of(mesh, zero_scale), HasSubstr("scale x must be a finite non-zero number"));

  MassOptions nan_scale;
  nan_scale.scale = Eigen::Vector3d(1.0, 1.0, std::numeric_limits<double>::quiet_NaN());
  EXPECT_THAT(error_of(mesh, nan_scale), HasSubstr("scale z must be a finite non-zero number"));

  MassOptions both;
  both.density = 1000.0;
  both.mass = 2.0;
  EXPECT_THAT(error_of(mesh, both), HasSubstr("either a density or a mass, not both"));

  MassOptions zero_mass;
  zero_mass.mass = 0.0;
  EXPECT_THAT(error_of(mesh, zero_mass), HasSubstr("mass must be a positive finite number"));

  MassOptions zero_thickness;
  zero_thickness.shell_thickness = 0.0;
  EXPECT_THAT(error_of(mesh, zero_thickness),
              HasSubstr("shell thickness must be a positive finite number"));
}

// ---------------------------------------------------------------------------------------------
// Repaired meshes: the fix is made, reported, and the numbers are right.

TEST(MeshChecks, AllFacesInvertedAreFlippedWithAWarning) {
  const Eigen::Vector3d size(0.5, 1.5, 2.5);
  const MeshReport report =
      analyze_mesh(reversed(box(size, {1.0, 2.0, 3.0})), with_density(2.0), "inside_out.obj");
  EXPECT_TRUE(report.flipped);
  EXPECT_TRUE(report.watertight);
  EXPECT_THAT(report.warnings, ElementsAre(AllOf(HasSubstr("point inward"), HasSubstr("flipped"))));
  EXPECT_NEAR(report.volume, size.prod(), kExact * size.prod());
  expect_vector_near(report.mass_properties.center_of_mass, {1.0, 2.0, 3.0}, 1e-14);
  expect_inertia_near(report.mass_properties.inertia, box_inertia(2.0, size));
}

TEST(MeshAnalysisScale, NegativeFactorMirrorsWithoutFlipping) {
  // A turned box off the origin (products of inertia non-zero), mirrored in x, then scaled
  // per axis: the closed form of its image under diag(scale) (volume element |det|).
  const Eigen::Matrix3d turn =
      Eigen::AngleAxisd(0.6, Eigen::Vector3d(1, -2, 2).normalized()).toRotationMatrix();
  const Eigen::Vector3d centre(1.0, 2.0, 3.0);
  const Eigen::Vector3d size(0.5, 1.5, 2.5);
  TriangleMesh mesh = box_mesh(size);
  transform_mesh(mesh, turn, centre);
  const mesh_fixtures::SolidMoments solid =
      mesh_fixtures::box_moments(-size / 2, size / 2).transformed(turn, centre);
  for (const Eigen::Vector3d& scale :
       {Eigen::Vector3d(-1, 1, 1), Eigen::Vector3d(-1, 2, 0.5), Eigen::Vector3d(-1, -1, -1)}) {
    MassOptions options = with_density(2.0);
    options.scale = scale;
    const MeshReport report = analyze_mesh(mesh, options, "mirrored.stl");
    const mesh_fixtures::SolidMoments expected =
        solid.transformed(scale.asDiagonal(), Eigen::Vector3d::Zero());
    EXPECT_FALSE(report.flipped) << scale.transpose();
    EXPECT_THAT(report.warnings, IsEmpty());
    EXPECT_GT(report.volume, 0.0);
    EXPECT_NEAR(report.volume, std::abs(scale.prod()) * size.prod(), kExact * report.volume);
    expect_vector_near(report.mass_properties.center_of_mass, expected.center_of_mass(), 1e-13);
    expect_inertia_near(report.mass_properties.inertia, expected.inertia(2.0));
  }
  // The pure mirror negates the centre's x and the products with x, and keeps the rest.
  MassOptions mirror = with_density(2.0);
  mirror.scale = {-1, 1, 1};
  const MeshReport plain = analyze_mesh(mesh, with_density(2.0), "plain.stl");
  const MeshReport mirrored = analyze_mesh(mesh, mirror, "mirrored.stl");
  const Eigen::Matrix3d& I = plain.mass_properties.inertia;
  const Eigen::Matrix3d& J = mirrored.mass_properties.inertia;
  EXPECT_GT(std::abs(I(0, 1)), 1e-3 * largest_moment(I));
  const Eigen::Matrix3d sign = Eigen::Vector3d(-1, 1, 1).asDiagonal();
  expect_inertia_near(J, sign * I * sign);
  EXPECT_NEAR(mirrored.mass_properties.center_of_mass.x(),
              -plain.mass_properties.center_of_mass.x(), 1e-14);
}

TEST(MeshChecks, DegenerateTrianglesAreSkippedAndCounted) {
  const Eigen::Vector3d size(1.0, 2.0, 3.0);
  TriangleMesh mesh = box_mesh(size);
  const MeshReport clean = analyze_mesh(mesh, with_density(1.0), "clean");
  // A repeated index, and a triangle whose two distinct vertices sit at the same position
  // (degenerate only after welding).
  mesh.triangles.push_back({0, 0, 5});
  mesh.positions.push_back(mesh.positions[3]);
  mesh.triangles.push_back({3, 7, 8});
  const MeshReport report = analyze_mesh(mesh, with_density(1.0), "dirty");
  EXPECT_EQ(report.input_triangles, 14u);
  EXPECT_EQ(report.degenerate_triangles, 2u);
  EXPECT_EQ(report.triangles, 12u);
  EXPECT_EQ(report.welded_vertices, 1u);
  EXPECT_TRUE(report.watertight);
  EXPECT_THAT(report.warnings, ElementsAre(HasSubstr("skipped 2 degenerate triangles")));
  EXPECT_EQ(report.volume, clean.volume);
  EXPECT_EQ(report.mass_properties.center_of_mass, clean.mass_properties.center_of_mass);
  EXPECT_EQ(report.mass_properties.inertia, clean.mass_properties.inertia);
}

TEST(MeshChecks, UnweldedVerticesAreWelded) {
  const Eigen::Vector3d size(1.0, 2.0, 3.0);
  const TriangleMesh welded = box_mesh(size);
  TriangleMesh soup;
  for (const auto& t : welded.triangles) {
    const auto base = static_cast<std::uint32_t>(soup.positions.size());
    for (const std::uint32_t v : t) soup.positions.push_back(welded.positions[v]);
    soup.triangles.push_back({base, base + 1, base + 2});
  }
  const MeshReport report = analyze_mesh(soup, with_density(1.0), "soup.stl");
  EXPECT_EQ(report.welded_vertices, 36u - 8u);
  EXPECT_EQ(report.vertices, 8u);
  EXPECT_EQ(report.parts, 1u);
  EXPECT_EQ(report.boundary_edges, 0u);
  EXPECT_TRUE(report.watertight);
  EXPECT_THAT(report.warnings, IsEmpty());
  expect_inertia_near(report.mass_properties.inertia, box_inertia(1.0, size));
}

TEST(MeshChecks, LargeMeshSelfIntersectionCountedAsTheGridAloneCountsIt) {
  // 250,000 faces: the size at which the analysis finds the topology on two threads and the
  // overlap checks certify coarse regions whole. A patch of the tube's outer wall pushed in
  // through its inner wall must be refused with as many crossing pairs as the fine grid and
  // filter alone (no regions) find; the untouched torus passes.
  TriangleMesh torus = torus_mesh(1.0, 0.3, 500, 250);
  ASSERT_GE(torus.triangles.size(), 200'000u);
  const MeshReport clean = analyze_mesh(torus, with_density(1.0), "torus.stl");
  EXPECT_THAT(clean.warnings, IsEmpty());
  for (Eigen::Vector3d& p : torus.positions) {
    if (p.x() > 1.25 && std::abs(p.y()) < 0.05) p.x() -= 0.7;
  }
  const Topology topology = analyze_topology(torus);
  // The regions are usable and certify most cells, not those of the crossing.
  const detail::PartOverlaps certified =
      detail::find_part_overlaps(torus, topology.triangle_part, topology.parts);
  EXPECT_GT(certified.stats.certified, certified.stats.regions / 2);
  EXPECT_LT(certified.stats.certified, certified.stats.regions);
  detail::OverlapOptions grid_only;
  grid_only.method = detail::FacePairMethod::kFiltered;
  const detail::PartOverlaps expected =
      detail::find_part_overlaps(torus, topology.triangle_part, topology.parts, grid_only);
  ASSERT_EQ(expected.findings.size(), 1u);
  ASSERT_GT(expected.findings[0].face_pairs, 0u);
  EXPECT_THAT(error_of(torus, with_density(1.0), "tangled.stl"),
              HasSubstr("tangled.stl: part 1 of 1 intersects itself (" +
                        std::to_string(expected.findings[0].face_pairs) + " pairs of faces"));
  // Without the checks the crossing goes unnoticed (nothing certified, nothing found).
  MassOptions unchecked = with_density(1.0);
  unchecked.check_overlap = false;
  EXPECT_THAT(analyze_mesh(torus, unchecked, "tangled.stl").warnings, IsEmpty());
}

TEST(MeshChecks, DisjointPartsAreSummed) {
  const Eigen::Vector3d size_a(1.0, 2.0, 1.5), size_b(0.5, 0.5, 3.0);
  const Eigen::Vector3d centre_a(-2.0, 0.5, 0.0), centre_b(3.0, -1.0, 2.0);
  const double rho = 10.0;
  const MeshReport report = analyze_mesh(joined(box(size_a, centre_a), box(size_b, centre_b)),
                                         with_density(rho), "two.obj");
  EXPECT_EQ(report.parts, 2u);
  EXPECT_EQ(report.cavities, 0u);
  EXPECT_THAT(report.warnings, IsEmpty());

  const double ma = rho * size_a.prod(), mb = rho * size_b.prod();
  const Eigen::Vector3d com = (ma * centre_a + mb * centre_b) / (ma + mb);
  EXPECT_NEAR(report.mass_properties.mass, ma + mb, kExact * (ma + mb));
  expect_vector_near(report.mass_properties.center_of_mass, com, 1e-14 * 4.0);
  expect_inertia_near(report.mass_properties.inertia,
                      shifted(box_inertia(rho, size_a), ma, centre_a - com) +
                          shifted(box_inertia(rho, size_b), mb, centre_b - com));
}

TEST(MeshChecks, InwardInnerShellIsACavity) {
  const Eigen::Vector3d outer(4.0, 3.0, 2.0), inner(2.0, 1.0, 1.0);
  const Eigen::Vector3d centre(0.5, -0.25, 1.0);
  const double rho = 5.0;
  const MeshReport report = analyze_mesh(joined(box(outer, centre), reversed(box(inner, centre))),
                                         with_density(rho), "hollow.stl");
  EXPECT_EQ(report.parts, 2u);
  EXPECT_EQ(report.cavities, 1u);
  EXPECT_FALSE(report.flipped);
  EXPECT_THAT(report.warnings, IsEmpty());
  const double volume = outer.prod() - inner.prod();
  EXPECT_NEAR(report.volume, volume, kExact * volume);
  expect_vector_near(report.mass_properties.center_of_mass, centre, 1e-14);
  expect_inertia_near(report.mass_properties.inertia,
                      box_inertia(rho, outer) - box_inertia(rho, inner));
}

TEST(MeshChecks, OffCentreCavityMatchesRationalReference) {
  // The cavity off the outer box's centre moves the centre of mass; the exact oracle sums the
  // signed integrals of both shells.
  const Eigen::Vector3d centre(0.5, -0.25, 1.0);
  const TriangleMesh mesh =
      joined(box({4.0, 3.0, 2.0}, centre),
             reversed(box({1.0, 0.5, 0.75}, centre + Eigen::Vector3d(1.2, 0.7, 0.3))));
  const MeshReport report = analyze_mesh(mesh, with_density(7.0), "hollow.stl");
  EXPECT_EQ(report.cavities, 1u);
  const auto exact = rational_reference::rational_mass_properties(mesh, 7.0);
  EXPECT_NEAR(report.volume, exact.volume, kExact * exact.volume);
  expect_vector_near(report.mass_properties.center_of_mass, exact.center_of_mass, 1e-13);
  expect_inertia_near(report.mass_properties.inertia, exact.inertia);
}

TEST(MeshChecks, WholeHollowFileInsideOutIsFlippedAndKeepsItsCavity) {
  // Outer shell inward, inner shell outward: the whole file is inverted.
  const Eigen::Vector3d outer(4.0, 3.0, 2.0), inner(2.0, 1.0, 1.0);
  const MeshReport report =
      analyze_mesh(joined(reversed(box(outer, {0, 0, 0})), box(inner, {0, 0, 0})),
                   with_density(1.0), "hollow.stl");
  EXPECT_TRUE(report.flipped);
  EXPECT_EQ(report.cavities, 1u);
  EXPECT_THAT(report.warnings, ElementsAre(HasSubstr("flipped them all")));
  EXPECT_NEAR(report.volume, outer.prod() - inner.prod(), kExact * outer.prod());
  expect_inertia_near(report.mass_properties.inertia,
                      box_inertia(1.0, outer) - box_inertia(1.0, inner));
}

TEST(MeshChecks, LoneInsideOutPartIsFlippedWithAWarning) {
  const Eigen::Vector3d size_a(2.0, 2.0, 2.0), size_b(1.0, 0.5, 0.5);
  const Eigen::Vector3d centre_a(0.0, 0.0, 0.0), centre_b(5.0, 0.0, 0.0);
  const TriangleMesh good = joined(box(size_a, centre_a), box(size_b, centre_b));
  const MeshReport expected = analyze_mesh(good, with_density(1.0), "good");

  // The small part inside out, lying inside nothing: flipped, with a warning naming it.
  const MeshReport report = analyze_mesh(
      joined(box(size_a, centre_a), reversed(box(size_b, centre_b))), with_density(1.0), "bad.obj");
  EXPECT_FALSE(report.flipped);
  EXPECT_EQ(report.cavities, 0u);
  EXPECT_THAT(report.warnings,
              ElementsAre(HasSubstr("part 2 of 2 points inward but lies inside no other part: "
                                    "flipped it")));
  EXPECT_NEAR(report.volume, expected.volume, kExact * expected.volume);
  expect_vector_near(report.mass_properties.center_of_mass, expected.mass_properties.center_of_mass,
                     1e-14);
  expect_inertia_near(report.mass_properties.inertia, expected.mass_properties.inertia);

  // The big part inside out: the total is negative, so all are flipped, and then the small
  // one (now inside out) is flipped back. The body is still right.
  const MeshReport big = analyze_mesh(
      joined(reversed(box(size_a, centre_a)), box(size_b, centre_b)), with_density(1.0), "bad.obj");
  EXPECT_EQ(big.cavities, 0u);
  EXPECT_THAT(big.warnings, ::testing::Contains(HasSubstr("part 2 of 2 points inward")));
  EXPECT_NEAR(big.volume, expected.volume, kExact * expected.volume);
  expect_inertia_near(big.mass_properties.inertia, expected.mass_properties.inertia);
}

TEST(MeshChecks, NestedPartWithTheSameOrientationIsRefusedOrSummedWithAWarning) {
  const Eigen::Vector3d outer(4.0, 3.0, 2.0), inner(2.0, 1.0, 1.0);
  const TriangleMesh mesh = joined(box(outer, {0, 0, 0}), box(inner, {0, 0, 0}));
  MassOptions refusing = with_density(1.0);
  refusing.overlap = OverlapMode::kRefuse;
  EXPECT_THAT(error_of(mesh, refusing, "nested.stl"),
              AllOf(StartsWith("nested.stl: part 2 of 2 lies inside another part with the same "
                               "orientation, so its volume (2 m^3) would count twice"),
                    HasSubstr("give --overlap union to take their exact union or --overlap sum")));
  MassOptions options = with_density(1.0);
  options.overlap = OverlapMode::kSum;
  const MeshReport report = analyze_mesh(mesh, options, "nested.stl");
  EXPECT_EQ(report.cavities, 0u);
  EXPECT_THAT(
      report.warnings,
      ElementsAre(AllOf(HasSubstr("part 2 of 2 lies inside another part with the same orientation"),
                        HasSubstr("counts twice"))));
  // The integral adds both solids: that is what the warning says.
  EXPECT_NEAR(report.volume, outer.prod() + inner.prod(), kExact * outer.prod());
  expect_inertia_near(report.mass_properties.inertia,
                      box_inertia(1.0, outer) + box_inertia(1.0, inner));
}

TEST(MeshChecks, SolidInsideACavityIsNotCountedTwice) {
  // A ball in a hollow shell (a rattle): outer box, inward cavity, and a solid core inside the
  // cavity. The core does not overlap any matter, so nothing is counted twice.
  const Eigen::Vector3d outer(4.0, 4.0, 4.0), cavity(3.0, 3.0, 3.0), core(1.0, 1.0, 1.0);
  TriangleMesh mesh = joined(box(outer, {0, 0, 0}), reversed(box(cavity, {0, 0, 0})));
  append_mesh(mesh, box(core, {0, 0, 0}));
  const MeshReport report = analyze_mesh(mesh, with_density(1.0), "rattle.stl");
  EXPECT_EQ(report.parts, 3u);
  EXPECT_EQ(report.cavities, 1u);
  EXPECT_NEAR(report.volume, 64.0 - 27.0 + 1.0, kExact * 64.0);
  expect_inertia_near(report.mass_properties.inertia,
                      box_inertia(1.0, outer) - box_inertia(1.0, cavity) + box_inertia(1.0, core));
  // The shells around the core (outer +1, cavity -1) put it in no matter: no warning.
  EXPECT_THAT(report.warnings, IsEmpty());
}

TEST(MeshChecks, InsideOutPartInANotchIsNotACavity) {
  // An L-shaped prism and a small inside-out box in its notch: the box's bounding box lies in
  // the L's, but the box is outside the L (winding number 0), so it is flipped, not a cavity.
  const std::vector<Eigen::Vector2d> outline = {{0, 0}, {3, 0}, {3, 1}, {1, 1}, {1, 3}, {0, 3}};
  const TriangleMesh ell = extrude_polygon(outline, 0.0, 1.0);
  const TriangleMesh small = box({0.5, 0.5, 0.5}, {2.0, 2.0, 0.5});
  const MeshReport expected = analyze_mesh(joined(ell, small), with_density(1.0), "good");
  const MeshReport report = analyze_mesh(joined(ell, reversed(small)), with_density(1.0), "notch");
  EXPECT_EQ(report.cavities, 0u);
  EXPECT_THAT(report.warnings, ElementsAre(HasSubstr("part 2 of 2 points inward")));
  EXPECT_NEAR(report.volume, 5.0 + 0.125, kExact * 5.0);
  expect_vector_near(report.mass_properties.center_of_mass, expected.mass_properties.center_of_mass,
                     1e-14);
  expect_inertia_near(report.mass_properties.inertia, expected.mass_properties.inertia);
}

TEST(MeshChecks, UnreferencedVerticesDoNotChangeTheResult) {
  // A vertex no triangle uses (PLY and OBJ files may carry them; a skipped degenerate triangle
  // can also leave one behind) is not part of the body.
  // The reference point of every integral is the centre of the used vertices' bounding box: a
  // stray vertex far away must not move it (at 1e8 m the integrals would cancel
  // catastrophically).
  const Eigen::Vector3d size(1.0, 2.0, 3.0);
  const MeshReport clean = analyze_mesh(box_mesh(size), with_density(1.0), "clean");
  for (const double distance : {1e6, 1e8}) {
    SCOPED_TRACE(distance);
    TriangleMesh stray = box_mesh(size);
    stray.positions.push_back(Eigen::Vector3d::Constant(distance));
    TriangleMesh orphaned = box_mesh(size);  // the far vertex used only by a degenerate triangle
    orphaned.positions.push_back(Eigen::Vector3d::Constant(-distance));
    orphaned.triangles.push_back({0, 0, 8});
    for (const TriangleMesh* mesh : {&stray, &orphaned}) {
      try {
        const MeshReport report = analyze_mesh(*mesh, with_density(1.0), "stray.ply");
        EXPECT_NEAR(report.volume, clean.volume, kExact * clean.volume);
        expect_vector_near(report.mass_properties.center_of_mass, Eigen::Vector3d::Zero(), 1e-12);
        expect_inertia_near(report.mass_properties.inertia, clean.mass_properties.inertia);
      } catch (const InputError& error) {
        ADD_FAILURE() << "rejected: " << error.what();
      }
    }
  }
}

TEST(MeshChecks, NonManifoldEdgesAreWarnedAbout) {
  // Two unit cubes sharing one edge: closed, volume 2, one edge used by four triangles.
  TriangleMesh mesh = joined(box({1, 1, 1}, {0.5, 0.5, 0.5}), box({1, 1, 1}, {-0.5, -0.5, 0.5}));
  const MeshReport report = analyze_mesh(mesh, with_density(1.0), "kissing.stl");
  EXPECT_EQ(report.non_manifold_edges, 1u);
  EXPECT_EQ(report.parts, 1u);
  EXPECT_TRUE(report.watertight);
  EXPECT_THAT(report.warnings, ElementsAre(HasSubstr("1 edge shared by more than two triangles")));
  EXPECT_NEAR(report.volume, 2.0, kExact);
}

TEST(MeshChecks, ReportCountsAndBounds) {
  TriangleMesh mesh = box({1.0, 2.0, 3.0}, {10.0, 20.0, 30.0});
  const MeshReport report = analyze_mesh(mesh, with_density(1.0), "box.ply");
  EXPECT_EQ(report.source, "box.ply");
  EXPECT_EQ(report.input_triangles, 12u);
  EXPECT_EQ(report.triangles, 12u);
  EXPECT_EQ(report.vertices, 8u);
  EXPECT_EQ(report.parts, 1u);
  EXPECT_FALSE(report.shell);
  EXPECT_EQ(report.bounds_min, Eigen::Vector3d(9.5, 19.0, 28.5));
  EXPECT_EQ(report.bounds_max, Eigen::Vector3d(10.5, 21.0, 31.5));
  // Principal frame of the box: ascending moments, about z, y, x.
  const Eigen::Matrix3d expected = box_inertia(1.0, {1.0, 2.0, 3.0});
  expect_vector_near(report.principal.moments, {expected(2, 2), expected(1, 1), expected(0, 0)},
                     kExact * expected(0, 0));
}

// ---------------------------------------------------------------------------------------------
// Shell mode: area-weighted, open surfaces allowed.

TEST(ShellMode, OpenSquarePlate) {
  // A square of side a in the xy plane (an open surface: 4 boundary edges), thickness t.
  const double a = 0.8, t = 0.002, rho = 2700.0;
  const TriangleMesh plate{{{0, 0, 0}, {a, 0, 0}, {a, a, 0}, {0, a, 0}}, {{0, 1, 2}, {0, 2, 3}}};
  MassOptions options;
  options.density = rho;
  options.shell_thickness = t;
  const MeshReport report = analyze_mesh(plate, options, "plate.stl");
  EXPECT_TRUE(report.shell);
  EXPECT_FALSE(report.watertight);
  EXPECT_EQ(report.boundary_edges, 4u);
  EXPECT_EQ(report.thickness, t);
  EXPECT_NEAR(report.area, a * a, kExact * a * a);
  EXPECT_NEAR(report.volume, a * a * t, kExact * a * a * t);
  const double m = rho * a * a * t;
  EXPECT_NEAR(report.mass_properties.mass, m, kExact * m);
  expect_vector_near(report.mass_properties.center_of_mass, {a / 2, a / 2, 0.0}, 1e-15);
  const Eigen::Matrix3d expected =
      Eigen::Vector3d(m * a * a / 12, m * a * a / 12, m * a * a / 6).asDiagonal();
  expect_inertia_near(report.mass_properties.inertia, expected);

  // Winding does not matter for a shell.
  const MeshReport flipped = analyze_mesh(reversed(plate), options, "plate.stl");
  EXPECT_FALSE(flipped.flipped);
  expect_inertia_near(flipped.mass_properties.inertia, expected);
}

TEST(ShellMode, SphereSurfaceConvergesToTwoThirdsMR2) {
  // Thin spherical shell: I = 2/3 m r^2, m = rho 4 pi r^2 t; icosphere errors fall as 4^-k.
  const double r = 0.5, t = 0.001, rho = 1000.0;
  MassOptions options;
  options.density = rho;
  options.shell_thickness = t;
  std::vector<double> errors;
  for (const int subdivisions : {2, 3, 4, 5}) {
    const MeshReport report = analyze_mesh(icosphere_mesh(r, subdivisions), options, "ball.stl");
    const MassProperties& mp = report.mass_properties;
    EXPECT_NEAR(mp.mass, rho * report.area * t, kExact * mp.mass);
    // Icosahedral symmetry makes the tensor isotropic.
    expect_inertia_near(mp.inertia, mp.inertia.trace() / 3.0 * Eigen::Matrix3d::Identity(), 1e-12);
    errors.push_back(std::abs(mp.inertia(0, 0) / mp.mass - 2.0 / 3.0 * r * r) /
                     (2.0 / 3.0 * r * r));
    EXPECT_NEAR(report.area, 4.0 * std::numbers::pi * r * r, 0.05 * 4.0 * std::numbers::pi * r * r);
  }
  for (std::size_t k = 0; k + 1 < errors.size(); ++k) {
    const double order = std::log2(errors[k] / errors[k + 1]);  // per halving of the edge
    EXPECT_GE(order, 1.8) << k;
    EXPECT_LE(order, 2.2) << k;
  }
  EXPECT_LT(errors.back(), 1e-3);
}

TEST(ShellMode, GivenMassSetsDensityFromShellVolume) {
  const double r = 0.5, t = 0.01;
  MassOptions options;
  options.mass = 3.0;
  options.shell_thickness = t;
  const MeshReport report = analyze_mesh(icosphere_mesh(r, 3), options, "ball.stl");
  EXPECT_NEAR(report.volume, report.area * t, kExact * report.volume);
  EXPECT_NEAR(report.density, 3.0 / report.volume, kExact * report.density);
  EXPECT_NEAR(report.mass_properties.mass, 3.0, kExact * 3.0);
}

TEST(ShellMode, ZeroAreaIsAnError) {
  // Triangles with three distinct but collinear vertices survive welding yet have no area.
  const TriangleMesh line{{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, {{0, 1, 2}, {0, 2, 1}}};
  MassOptions options;
  options.shell_thickness = 0.01;
  EXPECT_THAT(error_of(line, options), HasSubstr("zero surface area"));
}

}  // namespace
}  // namespace tumble::engine
