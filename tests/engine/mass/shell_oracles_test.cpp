// The shell method (analyze_mesh with InertiaMethod::shell) against closed forms. The model:
// the mesh itself is the mid-surface, of zero geometric thickness, carrying a uniform areal
// density sigma (= density x thickness with --shell T, = mass / area with --mass M); the
// thickness only sets the mass. Oracles: a box's surface and a polygonal tube exactly, a
// sphere's and a circular tube's closed forms as the limits of tessellations converging at
// O(1/n^2) (observed order measured at n, 2n, 4n), and a thick spherical shell, from which the
// mid-surface model differs by O(t^2/R^2).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "engine/geometry/primitive_meshes.hpp"
#include "engine/mass/mesh_analysis.hpp"
#include "inertia_expectations.hpp"

namespace tumble::engine {
namespace {

using testing::expect_inertia_near;
using testing::expect_vector_near;
using testing::kExact;

MassProperties shell_by_mass(const TriangleMesh& mesh, double mass) {
  MassOptions options;
  options.inertia = InertiaMethod::shell;
  options.mass = mass;
  return analyze_mesh(mesh, options, "shell.stl").mass_properties;
}

/// The lateral surface of the prism on a regular `sides`-gon inscribed in a circle of `radius`,
/// axis z, z in [-height/2, height/2]: no caps, so 2 boundary loops.
TriangleMesh open_tube(double radius, double height, int sides) {
  TriangleMesh mesh;
  const auto n = static_cast<std::uint32_t>(sides);
  for (const double z : {-height / 2, height / 2}) {
    for (std::uint32_t k = 0; k < n; ++k) {
      const double angle = 2.0 * std::numbers::pi * k / n;
      mesh.positions.emplace_back(radius * std::cos(angle), radius * std::sin(angle), z);
    }
  }
  for (std::uint32_t k = 0; k < n; ++k) {
    const std::uint32_t next = (k + 1) % n;
    mesh.triangles.push_back({k, next, n + next});
    mesh.triangles.push_back({k, n + next, n + k});
  }
  return mesh;
}

/// Observed orders log2(e_k / e_{k+1}) of errors measured at n, 2n, 4n, ...
std::vector<double> observed_shell_orders(const std::vector<double>& errors) {
  std::vector<double> orders;
  for (std::size_t k = 0; k + 1 < errors.size(); ++k) {
    orders.push_back(std::log2(errors[k] / errors[k + 1]));
  }
  return orders;
}

void expect_shell_second_order(const std::vector<double>& errors) {
  for (const double order : observed_shell_orders(errors)) {
    EXPECT_GE(order, 1.8);
    EXPECT_LE(order, 2.2);
  }
}

TEST(ShellOracles, BoxSurfaceMatchesClosedFormPerAxis) {
  // Box of sides a, b, c (x, y, z), surface at areal density sigma: m = 2 sigma (ab + bc + ca).
  // I_xx = integral of (y^2 + z^2) dm over the six faces:
  //   the two faces x = +-a/2 (b by c each): sigma bc (b^2 + c^2) / 12 each;
  //   the two faces y = +-b/2 (a by c):      sigma ac (b^2/4 + c^2/12) each;
  //   the two faces z = +-c/2 (a by b):      sigma ab (b^2/12 + c^2/4) each;
  // so I_xx = m [bc (b^2 + c^2) + ac (3b^2 + c^2) + ab (b^2 + 3c^2)] / (12 (ab + bc + ca)),
  // and I_yy, I_zz by turning (a, b, c). A cube of side s gives 5/18 m s^2.
  const double a = 0.3, b = 0.5, c = 0.7, m = 2.5;
  const auto moment = [m](double across, double u, double v) {  // about the axis along `across`
    const double faces = across * u + u * v + v * across;
    return m *
           (u * v * (u * u + v * v) + across * v * (3 * u * u + v * v) +
            across * u * (u * u + 3 * v * v)) /
           (12 * faces);
  };
  const MassProperties box = shell_by_mass(box_mesh({a, b, c}), m);
  EXPECT_NEAR(box.mass, m, kExact * m);
  expect_vector_near(box.center_of_mass, Eigen::Vector3d::Zero(), 1e-15);
  const Eigen::Matrix3d expected =
      Eigen::Vector3d(moment(a, b, c), moment(b, c, a), moment(c, a, b)).asDiagonal();
  expect_inertia_near(box.inertia, expected);
  EXPECT_NEAR(moment(1, 1, 1), 5.0 / 18.0 * m, 1e-15);
}

TEST(ShellOracles, PolygonalTubeIsExactAndConvergesToTheCircularTube) {
  // A side of the n-gon tube has length s = 2R sin(pi/n) at distance d = R cos(pi/n) from the
  // axis: integral of r^2 along it is s (d^2 + s^2/12), so I_axis = m R^2 (1 - 2/3 sin^2(pi/n))
  // exactly; a regular polygon's second moment is isotropic, so I_perp = I_axis / 2 + m h^2/12.
  // Circle (n -> oo): I_axis = m R^2, I_perp = m (R^2/2 + h^2/12); the error is O(1/n^2).
  const double radius = 0.2, height = 0.6, m = 1.5;
  std::vector<double> axis_errors, perpendicular_errors;
  for (const int sides : {12, 24, 48}) {
    const MassProperties tube = shell_by_mass(open_tube(radius, height, sides), m);
    const double shrink = std::pow(std::sin(std::numbers::pi / sides), 2);
    const double axis = m * radius * radius * (1 - 2.0 / 3.0 * shrink);
    const double perpendicular = axis / 2 + m * height * height / 12;
    expect_inertia_near(tube.inertia,
                        Eigen::Vector3d(perpendicular, perpendicular, axis).asDiagonal());
    expect_vector_near(tube.center_of_mass, Eigen::Vector3d::Zero(), 1e-15);
    const double circle_axis = m * radius * radius;
    const double circle_perpendicular = m * (radius * radius / 2 + height * height / 12);
    axis_errors.push_back(std::abs(tube.inertia(2, 2) - circle_axis) / circle_axis);
    perpendicular_errors.push_back(std::abs(tube.inertia(0, 0) - circle_perpendicular) /
                                   circle_perpendicular);
  }
  expect_shell_second_order(axis_errors);
  expect_shell_second_order(perpendicular_errors);
  EXPECT_LT(axis_errors.back(), 3e-3);  // 2/3 sin^2(pi/48)
}

TEST(ShellOracles, UvSphereConvergesToTwoThirdsMR2AtSecondOrder) {
  // Thin spherical shell: I = 2/3 m R^2 about any axis through the centre. The UV sphere's
  // triangles lie inside the sphere by O(h^2): the mean moment (trace / 3) errs by O(1/n^2).
  const double radius = 0.4, m = 2.0;
  const double sphere = 2.0 / 3.0 * m * radius * radius;
  std::vector<double> errors;
  for (const int segments : {8, 16, 32}) {
    const MassProperties ball = shell_by_mass(uv_sphere_mesh(radius, segments, segments / 2), m);
    errors.push_back(std::abs(ball.inertia.trace() / 3 - sphere) / sphere);
  }
  expect_shell_second_order(errors);
  EXPECT_LT(errors.back(), 1.5e-2);
}

TEST(ShellOracles, ThicknessSetsTheMassOfAMidSurfaceShell) {
  // With --shell T the mass is density x area x T and the inertia is the mid-surface's: a thick
  // spherical shell of radii R -+ T/2 has I = 2/5 m (r2^5 - r1^5) / (r2^3 - r1^3), which is
  // for the same mass 2/3 m R^2 (1 + T^2/(2R^2)) / (1 + T^2/(12R^2)), i.e. 5/12 (T/R)^2 more
  // to leading order: 1.7e-4 at T/R = 1/50.
  const double radius = 0.5, thickness = 0.01, density = 7800.0;
  MassOptions options;
  options.density = density;
  options.shell_thickness = thickness;
  const MeshReport report = analyze_mesh(icosphere_mesh(radius, 3), options, "ball.stl");
  const MassProperties& shell = report.mass_properties;
  EXPECT_NEAR(shell.mass, density * report.area * thickness, kExact * shell.mass);
  const double mean_moment = shell.inertia.trace() / 3;
  // The same surface given its mass instead: the same inertia.
  expect_inertia_near(shell_by_mass(icosphere_mesh(radius, 3), shell.mass).inertia, shell.inertia);
  const double r1 = radius - thickness / 2, r2 = radius + thickness / 2;
  const double thick =
      0.4 * shell.mass * (std::pow(r2, 5) - std::pow(r1, 5)) / (std::pow(r2, 3) - std::pow(r1, 3));
  const double mid_surface = 2.0 / 3.0 * shell.mass * radius * radius;
  const double model_gap = std::abs(thick - mid_surface) / mid_surface;
  const double ratio_squared = std::pow(thickness / radius, 2);
  EXPECT_NEAR(model_gap, 5.0 / 12.0 * ratio_squared, 1e-3 * ratio_squared);
  // The tessellation (icosphere, 3 subdivisions) is the larger error here; within 1%.
  EXPECT_NEAR(mean_moment, mid_surface, 1e-2 * mid_surface);
}

}  // namespace
}  // namespace tumble::engine
