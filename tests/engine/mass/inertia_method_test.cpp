// The inertia methods of analyze_mesh on meshes exact refuses: the convex hull's solid, the
// surface as a thin shell, and exact with a named fallback to the hull. Oracles: closed forms of
// the box, of a box's surface (I = m s^2 5/18 about the centre for a cube of side s) and of a
// prism over the L's hull polygon (mesh_fixtures::prism_moments, Green's theorem).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "engine/geometry/primitive_meshes.hpp"
#include "engine/mass/mesh_analysis.hpp"
#include "engine/mesh_fixtures.hpp"
#include "inertia_expectations.hpp"
#include "support/input_error.hpp"

namespace tumble::engine {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::IsEmpty;

MassOptions method_options(InertiaMethod method) {
  MassOptions options;
  options.inertia = method;
  options.density = 2.0;
  return options;
}

/// The cube of side `side` centred at the origin, without its two triangles at z = +side/2.
TriangleMesh open_box(double side) {
  TriangleMesh mesh = box_mesh(Eigen::Vector3d::Constant(side));
  const auto on_top = [&](const std::array<std::uint32_t, 3>& t) {
    return std::all_of(t.begin(), t.end(),
                       [&](std::uint32_t v) { return mesh.positions[v].z() > 0.25 * side; });
  };
  std::erase_if(mesh.triangles, on_top);
  return mesh;
}

/// The L outline (counter-clockwise; star-shaped from its first corner) and its hull.
const std::vector<Eigen::Vector2d> kLOutline = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
const std::vector<Eigen::Vector2d> kLHull = {{0, 0}, {2, 0}, {2, 1}, {1, 2}, {0, 2}};

/// The prism over kLOutline from z = 0 to z = 1, caps fanned from the first corner.
TriangleMesh l_prism() {
  TriangleMesh mesh;
  const auto n = static_cast<std::uint32_t>(kLOutline.size());
  for (double z : {0.0, 1.0}) {
    for (const Eigen::Vector2d& p : kLOutline) mesh.positions.emplace_back(p.x(), p.y(), z);
  }
  for (std::uint32_t i = 1; i + 1 < n; ++i) {
    mesh.triangles.push_back({0, i + 1, i});          // bottom, facing -z
    mesh.triangles.push_back({n, n + i, n + i + 1});  // top, facing +z
  }
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t j = (i + 1) % n;
    mesh.triangles.push_back({i, j, n + j});
    mesh.triangles.push_back({i, n + j, n + i});
  }
  return mesh;
}

Eigen::Matrix3d cube_inertia(double mass, double side) {
  return Eigen::Matrix3d::Identity() * mass * side * side / 6.0;
}

TEST(InertiaMethodTest, NamesRoundTrip) {
  for (InertiaMethod method : {InertiaMethod::exact, InertiaMethod::convex, InertiaMethod::shell,
                               InertiaMethod::legacy, InertiaMethod::automatic}) {
    EXPECT_EQ(parse_inertia_method(inertia_method_name(method)), method);
  }
  EXPECT_EQ(inertia_method_name(InertiaMethod::automatic), "auto");
  EXPECT_EQ(inertia_method_name(InertiaMethod::legacy), "legacy");
  EXPECT_FALSE(parse_inertia_method("automatic").has_value());
}

TEST(HullInertiaTest, CubeHullIsTheCube) {
  const double side = 0.3;
  const MeshReport report = analyze_mesh(box_mesh(Eigen::Vector3d::Constant(side)),
                                         method_options(InertiaMethod::convex), "cube.stl");
  EXPECT_EQ(report.method, InertiaMethod::convex);
  EXPECT_NEAR(report.volume, side * side * side, 1e-15);
  ASSERT_TRUE(report.enclosed_volume.has_value());
  EXPECT_NEAR(*report.enclosed_volume, side * side * side, 1e-15);
  EXPECT_NEAR(report.mass_properties.mass, 2.0 * side * side * side, 1e-15);
  testing::expect_vector_near(report.mass_properties.center_of_mass, Eigen::Vector3d::Zero(),
                              1e-15);
  testing::expect_inertia_near(report.mass_properties.inertia,
                               cube_inertia(report.mass_properties.mass, side));
  EXPECT_THAT(report.warnings, IsEmpty());
}

TEST(HullInertiaTest, OpenBoxExactRefusesConvexGivesTheBox) {
  const double side = 0.5;
  const std::string refused = tumble::testing::input_error_of(
      [&] { analyze_mesh(open_box(side), method_options(InertiaMethod::exact), "open.stl"); });
  EXPECT_THAT(refused,
              AllOf(HasSubstr("open.stl: the surface is open"), HasSubstr("4 boundary edges")));

  const MeshReport convex =
      analyze_mesh(open_box(side), method_options(InertiaMethod::convex), "open.stl");
  EXPECT_EQ(convex.method, InertiaMethod::convex);
  EXPECT_EQ(convex.boundary_edges, 4u);
  EXPECT_FALSE(convex.enclosed_volume.has_value());  // an open surface encloses nothing
  EXPECT_NEAR(convex.volume, side * side * side, 1e-15);
  testing::expect_inertia_near(convex.mass_properties.inertia,
                               cube_inertia(2.0 * side * side * side, side));
  EXPECT_THAT(convex.warnings, IsEmpty());  // convex was asked for: nothing fell back
}

TEST(HullInertiaTest, AutoFallsBackToTheHullNamingTheReason) {
  const double side = 0.5;
  const MeshReport report =
      analyze_mesh(open_box(side), method_options(InertiaMethod::automatic), "open.stl");
  EXPECT_EQ(report.method, InertiaMethod::convex);
  ASSERT_TRUE(report.fallback_reason.has_value());
  EXPECT_THAT(*report.fallback_reason, HasSubstr("the surface is open (4 boundary edges)"));
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_THAT(report.warnings[0], AllOf(HasSubstr("exact inertia refused"),
                                        HasSubstr("4 boundary edges"), HasSubstr("convex hull")));
  testing::expect_inertia_near(report.mass_properties.inertia,
                               cube_inertia(2.0 * side * side * side, side));
}

TEST(HullInertiaTest, AutoKeepsExactOnAClosedMesh) {
  const MeshReport report = analyze_mesh(l_prism(), method_options(InertiaMethod::automatic), "l");
  EXPECT_EQ(report.method, InertiaMethod::exact);
  EXPECT_FALSE(report.fallback_reason.has_value());
  EXPECT_NEAR(report.volume, 3.0, 1e-14);
  EXPECT_THAT(report.warnings, IsEmpty());
}

TEST(HullInertiaTest, LPrismHullAgainstClosedFormWarnsOfConcavity) {
  const MeshReport report = analyze_mesh(l_prism(), method_options(InertiaMethod::convex), "l");
  const mesh_fixtures::SolidMoments hull = mesh_fixtures::prism_moments(kLHull, 0.0, 1.0);
  EXPECT_NEAR(hull.volume, 3.5, 1e-14);  // the L's 3 plus the cut corner's half
  EXPECT_NEAR(report.volume, hull.volume, 1e-14);
  ASSERT_TRUE(report.enclosed_volume.has_value());
  EXPECT_NEAR(*report.enclosed_volume, 3.0, 1e-14);
  testing::expect_vector_near(report.mass_properties.center_of_mass, hull.center_of_mass(), 1e-14);
  testing::expect_inertia_near(report.mass_properties.inertia, hull.inertia(2.0));
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_THAT(report.warnings[0], AllOf(HasSubstr("convex hull's volume (3.5 m^3)"),
                                        HasSubstr("16.6667% more"), HasSubstr("encloses (3 m^3)")));
}

TEST(HullInertiaTest, FlatMeshHasNoHull) {
  TriangleMesh square;
  square.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  square.triangles = {{0, 1, 2}, {0, 2, 3}};
  const std::string message = tumble::testing::input_error_of(
      [&] { analyze_mesh(square, method_options(InertiaMethod::convex), "flat.obj"); });
  EXPECT_THAT(message, HasSubstr("flat.obj: "));
}

TEST(ShellInertiaTest, CubeSurfaceByMassMatchesClosedForm) {
  const double side = 0.4, mass = 3.0;
  MassOptions options;
  options.inertia = InertiaMethod::shell;
  options.mass = mass;
  const MeshReport report =
      analyze_mesh(box_mesh(Eigen::Vector3d::Constant(side)), options, "cube.stl");
  EXPECT_EQ(report.method, InertiaMethod::shell);
  EXPECT_TRUE(report.shell);
  EXPECT_NEAR(report.area, 6.0 * side * side, 1e-15);
  EXPECT_NEAR(report.areal_density, mass / (6.0 * side * side), 1e-12);
  EXPECT_EQ(report.thickness, 0.0);
  EXPECT_NEAR(report.mass_properties.mass, mass, 1e-14);
  // Each of the six faces holds m/6: two faces normal to an axis give 2 (m/6) s^2/6, the four
  // parallel to it 4 (m/6)(s^2/4 + s^2/12).
  testing::expect_inertia_near(report.mass_properties.inertia,
                               Eigen::Matrix3d::Identity() * mass * side * side * 5.0 / 18.0);
}

TEST(ShellInertiaTest, OpenBoxByThicknessIsFiveFaces) {
  const double side = 1.0, thickness = 0.01, density = 500.0;
  MassOptions options;
  options.inertia = InertiaMethod::shell;
  options.shell_thickness = thickness;
  options.density = density;
  const MeshReport report = analyze_mesh(open_box(side), options, "open.stl");
  const double face = density * thickness * side * side;  // mass of one face
  EXPECT_NEAR(report.mass_properties.mass, 5.0 * face, 1e-12);
  EXPECT_NEAR(report.areal_density, density * thickness, 1e-12);
  // Centre of mass: the bottom at -s/2 and four sides at 0, over five faces.
  testing::expect_vector_near(report.mass_properties.center_of_mass,
                              Eigen::Vector3d(0, 0, -0.5 * side / 5.0), 1e-14);
}

TEST(ShellInertiaTest, OptionsThatCannotGiveAShellAreRefused) {
  MassOptions options;
  options.inertia = InertiaMethod::shell;
  EXPECT_THAT(tumble::testing::input_error_of(
                  [&] { analyze_mesh(box_mesh(Eigen::Vector3d::Ones()), options, "a.stl"); }),
              HasSubstr("a.stl: the shell inertia method needs a thickness (--shell T) or a "
                        "total mass (--mass M)"));
  options.inertia = InertiaMethod::convex;
  options.shell_thickness = 0.01;
  EXPECT_THAT(tumble::testing::input_error_of(
                  [&] { analyze_mesh(box_mesh(Eigen::Vector3d::Ones()), options, "a.stl"); }),
              HasSubstr("a.stl: a shell thickness applies to the shell inertia method, not to "
                        "convex"));
}

}  // namespace
}  // namespace tumble::engine
