// The built-in stability cases (engine/PHYSICS.md §7): each a body and a dt sweep expressed
// through the case's natural rate (|w| dt, w3 dt, wn dt), so the matrix columns read across cases.
#include "app/analysis/stability_suite.hpp"

#include <cmath>

#include <Eigen/Geometry>

#include "app/scene/scene.hpp"
#include "base/errors.hpp"

namespace tumble::app {
namespace {

using engine::BodyModel;
using engine::BodyState;
using engine::spinning_state;

const Eigen::Quaterniond kTilted(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));

BodyModel free_body(const std::string& name, const Eigen::Vector3d& moments) {
  BodyModel body;
  body.name = name;
  body.mass = 1.0;
  body.moments = moments;
  return body;
}

/// A state turning at `omega_body` (principal axes) in orientation `q`.
/// The dt values for the dimensionless steps `rate_dts` at `rate` (1/s).
std::vector<double> steps_for(double rate, const std::vector<double>& rate_dts) {
  std::vector<double> dts;
  for (const double x : rate_dts) dts.push_back(x / rate);
  return dts;
}

/// A single free body spinning at `omega_body`, swept over |w| dt.
StabilityCase spin_case(std::string name, std::string description, const Eigen::Vector3d& moments,
                        const Eigen::Vector3d& omega_body, double duration,
                        const std::vector<double>& rate_dts) {
  StabilityCase c;
  c.name = std::move(name);
  c.description = std::move(description);
  const BodyModel body = free_body(c.name, moments);
  c.bodies = {body};
  c.initial = {spinning_state(body, kTilted, omega_body)};
  c.duration = duration;
  c.rate_label = "|w| dt";
  c.rate = omega_body.norm();
  c.dts = steps_for(c.rate, rate_dts);
  return c;
}

StabilityCase fast_spin(double duration, const std::vector<double>& rate_dts) {
  return spin_case("fast-spin", "body (1, 2, 3) spinning at 10 rad/s near its largest axis",
                   Eigen::Vector3d(1, 2, 3), 10.0 * Eigen::Vector3d(0.1, 0.2, 1.0).normalized(),
                   duration, rate_dts);
}

StabilityCase needle(double duration, const std::vector<double>& rate_dts) {
  return spin_case("needle",
                   "needle 1:1000:1000 spun at 100 rad/s about its axis, transverse wobble "
                   "0.01 rad/s",
                   Eigen::Vector3d(1, 1000, 1000), Eigen::Vector3d(100.0, 0.01, 0.0), duration,
                   rate_dts);
}

StabilityCase thin_disc(double duration, const std::vector<double>& rate_dts) {
  return spin_case("thin-disc",
                   "thin disc (1, 1, 2) spun at 20 rad/s about its axis, tilted 0.5 rad/s",
                   Eigen::Vector3d(1, 1, 2), Eigen::Vector3d(0.5, 0.0, 20.0), duration, rate_dts);
}

/// Heavy symmetric top: I about the centre of mass (1, 1, 0.5), mass 1 kg, centre of mass
/// 0.5 m up the axis from a fixed pivot, spin 50 rad/s, tilted 0.3 rad, gravity 9.81.
StabilityCase heavy_top(double duration, const std::vector<double>& rate_dts) {
  const double mass = 1.0, l = 0.5, g = 9.81, spin = 50.0, tilt = 0.3;
  BodyModel top =
      free_body("heavy-top", Eigen::Vector3d(1.0 + mass * l * l, 1.0 + mass * l * l, 0.5));
  top.mass = mass;
  top.pivoted = true;
  top.center_offset = Eigen::Vector3d(0.0, 0.0, l);
  top.forces = {engine::Gravity{Eigen::Vector3d(0.0, 0.0, -g)}};
  StabilityCase c;
  c.name = "heavy-top";
  c.description =
      "fast heavy symmetric top: I = (1, 1, 0.5) about the centre of mass 0.5 m above a pivot, "
      "spin 50 rad/s, tilted 0.3 rad, gravity";
  c.bodies = {top};
  c.initial = {spinning_state(top,
                              Eigen::Quaterniond(Eigen::AngleAxisd(tilt, Eigen::Vector3d::UnitX())),
                              Eigen::Vector3d(0.0, 0.0, spin))};
  c.duration = duration;
  c.rate_label = "w3 dt";
  c.rate = spin;
  c.dts = steps_for(spin, rate_dts);
  // The origin-free scale of engine/PHYSICS.md §6 less the spin energy L3^2 / (2 I3): L3 is an
  // invariant of its own for the symmetric top, so those 625 J never move and would hide every
  // drift. What is left is the energy the top trades between tilt, precession and nutation: the
  // transverse kinetic energy (0 here) plus gravity's swing m g l (1 + cos tilt) = 9.59 J.
  const double spin_momentum =
      (c.initial[0].orientation.conjugate() * c.initial[0].angular_momentum).z();
  c.energy_scale = engine::energy_scale(top, c.initial[0], duration) -
                   spin_momentum * spin_momentum / (2.0 * top.moments.z());
  c.note =
      "energy changes relative to the origin-free scale less the separately conserved spin "
      "energy I3 w3^2 / 2 = 625 J: m g l (1 + cos 0.3) = 9.59 J";
  return c;
}

/// A 2 kg bob on an 8 N/m spring (wn = 2 rad/s) released 0.5 m from its anchor.
StabilityCase stiff_spring(double duration, const std::vector<double>& rate_dts) {
  BodyModel bob = free_body("stiff-spring", Eigen::Vector3d::Constant(1e-3));
  bob.mass = 2.0;
  const double stiffness = 8.0;
  bob.forces = {
      engine::Spring{Eigen::Vector3d(0.0, 0.0, 1.0), Eigen::Vector3d::Zero(), stiffness, 0.0}};
  BodyState start;
  start.position = Eigen::Vector3d(0.5, 0.0, 1.0);
  StabilityCase c;
  c.name = "stiff-spring";
  c.description = "2 kg bob on an 8 N/m spring (wn = 2 rad/s) released 0.5 m from the anchor";
  c.bodies = {bob};
  c.initial = {start};
  c.duration = duration;
  c.rate_label = "wn dt";
  c.rate = std::sqrt(stiffness / bob.mass);
  c.dts = steps_for(c.rate, rate_dts);
  // Symplectic Euler's energy legitimately swings to 1 / (1 - wn dt / 2) = 20x at wn dt = 1.9.
  c.blowup_factor = 100.0;
  c.note =
      "blow-up factor 100: below wn dt = 2 symplectic Euler's energy swings to "
      "1 / (1 - wn dt / 2) times its initial value (20x at 1.9) and stays bounded";
  return c;
}

StabilityCase near_separatrix(double duration, const std::vector<double>& rate_dts) {
  return spin_case("near-separatrix",
                   "body (1, 2, 3) spun at 1 rad/s about its intermediate axis, perturbed 1e-3",
                   Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(1e-3, 1.0, 1e-3), duration, rate_dts);
}

/// 1e6 steps of the cheap symplectic integrators only.
StabilityCase long_run(double steps) {
  const double dt = 0.01;
  StabilityCase c =
      spin_case("long-run", "body (1, 2, 3) tumbling at 1.08 rad/s for 1e6 steps",
                Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(0.4, 0.8, 0.6), steps * dt, {});
  c.dts = {dt};
  c.description = "body (1, 2, 3) tumbling at 1.08 rad/s for " +
                  std::to_string(static_cast<long long>(steps)) + " steps";
  c.only_integrators = {"splitting", "semi-implicit-euler", "lie-euler"};
  c.skip_note = "long run: cheap integrators only";
  return c;
}

/// A tumbling body 1e6 m from the origin, moving: rounding of the position must not leak into
/// the rotation (and the straight-line motion must stay straight).
StabilityCase far_from_origin(double duration, const std::vector<double>& rate_dts) {
  StabilityCase c =
      spin_case("far-from-origin",
                "body (1, 2, 3) at x = 1e6 m moving at (3, -2, 1) m/s, tumbling at 5.4 rad/s",
                Eigen::Vector3d(1, 2, 3), 5.0 * Eigen::Vector3d(0.4, 0.8, 0.6), duration, rate_dts);
  c.initial[0].position = Eigen::Vector3d(1e6, 0.0, 0.0);
  c.initial[0].velocity = Eigen::Vector3d(3.0, -2.0, 1.0);
  return c;
}

StabilitySuite standard_suite() {
  return {"standard",
          "every case of engine/PHYSICS.md §7, a few seconds per integrator",
          {fast_spin(20.0, {0.1, 0.3, 1.0, 2.0, 3.0}), needle(10.0, {0.1, 1.0, 5.0}),
           thin_disc(10.0, {0.1, 0.5, 1.0, 2.0}), heavy_top(2.0, {0.05, 0.1, 0.2, 0.5, 1.0}),
           stiff_spring(150.0, {0.5, 1.0, 1.5, 1.9, 2.1, 3.0}),
           near_separatrix(40.0, {0.01, 0.05, 0.2, 0.5}), long_run(1e6),
           far_from_origin(20.0, {0.1, 0.5, 1.0})}};
}

StabilitySuite quick_suite() {
  return {
      "quick",
      "needle, heavy top and stiff spring with few steps (for tests)",
      {needle(1.0, {0.5, 5.0}), heavy_top(1.0, {0.2, 0.5}), stiff_spring(30.0, {1.5, 1.9, 2.1})}};
}

}  // namespace

std::vector<SuiteListing> stability_suite_listing() {
  std::vector<SuiteListing> listing;
  for (const StabilitySuite& suite : {standard_suite(), quick_suite()}) {
    std::string cases;
    for (const StabilityCase& c : suite.cases) cases += (cases.empty() ? "" : ", ") + c.name;
    listing.push_back({suite.name, suite.description + " (" + cases + ")"});
  }
  return listing;
}

StabilitySuite stability_suite(const std::string& name) {
  if (name == "standard") return standard_suite();
  if (name == "quick") return quick_suite();
  throw tumble::InputError("--suite: unknown suite '" + name +
                           "'; expected one of: standard, quick (see --list-suites)");
}

StabilityCase scene_case(const std::filesystem::path& file,
                         const std::optional<std::vector<double>>& dts) {
  const SceneDescription scene = load_scene(file);
  CompiledScene compiled = compile_scene(scene);
  StabilityCase c;
  c.name = scene.name;
  c.description = "scene " + file.string() + " (" + std::to_string(scene.bodies.size()) +
                  (scene.bodies.size() == 1 ? " body)" : " bodies)");
  c.bodies = std::move(compiled.bodies);
  c.initial = std::move(compiled.initial);
  c.duration = scene.duration;
  if (dts) {
    for (const double dt : *dts) {
      if (auto problem = step_problem(dt, scene.duration)) {
        throw tumble::InputError("--dts: for " + file.string() + ": " + *problem);
      }
    }
    c.dts = *dts;
  } else {
    // The scene's dt x {1, 2, 4, 8}, leaving out steps longer than the run.
    for (const double factor : {1.0, 2.0, 4.0, 8.0}) {
      if (!step_problem(factor * scene.dt, scene.duration)) c.dts.push_back(factor * scene.dt);
    }
  }
  if (scene.tolerance) c.tolerance = *scene.tolerance;
  if (scene.absolute_tolerance) c.absolute_tolerance = *scene.absolute_tolerance;
  return c;
}

}  // namespace tumble::app
