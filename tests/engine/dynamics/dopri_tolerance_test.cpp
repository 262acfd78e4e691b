// dopri's tolerances (engine/PHYSICS.md §3): the global error on the bench's scenes against
// their exact solutions, within 100 times the tolerance from 1e-4 to 1e-12; the turn per step
// capped; the relative tolerance scaling each quantity by its own size (a
// body scaled down by 2^-20 takes the very same steps); the absolute tolerance loosening the
// small quantities; and bad tolerances refused with the field named.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "base/errors.hpp"
#include "engine/body/rigid_body.hpp"
#include "engine/dynamics/integrators.hpp"
#include "engine/exact/lagrange_top.hpp"
#include "engine/exact/torque_free_exact.hpp"
#include "engine/simulation/simulation.hpp"
#include "support/bench_scene_bodies.hpp"
#include "support/input_error.hpp"

namespace tumble::engine {
namespace {

using ::testing::HasSubstr;

constexpr double kBenchTolerances[] = {1e-4, 1e-6, 1e-8, 1e-10, 1e-12};

/// What one dopri run of a bench scene measured: its largest orientation error over the output
/// instants (the scene's dt, as `tumble bench` samples) and its counts.
struct ToleranceRun {
  double worst = 0.0;  ///< rad
  StepCounts counts;
};

template <typename Exact>
ToleranceRun run_against(const testing::BenchSceneBody& scene, double tolerance,
                         const Exact& exact_orientation) {
  SimulationSettings settings;
  settings.integrator = IntegratorKind::kDopri;
  settings.dt = scene.dt;
  settings.duration = scene.duration;
  settings.tolerance = tolerance;
  settings.blowup_factor = std::numeric_limits<double>::infinity();
  Simulation simulation({scene.body}, {scene.initial}, settings);
  ToleranceRun run;
  while (simulation.step()) {
    run.worst = std::max(run.worst, orientation_angle(simulation.states()[0].orientation,
                                                      exact_orientation(simulation.time())));
  }
  EXPECT_TRUE(simulation.finished() && !simulation.blow_up());
  run.counts = simulation.step_counts();
  return run;
}

// The case: on the T-handle the largest orientation error was 1e6 times the tolerance
// (1.9 rad at 1e-6, 1.9e-6 rad at 1e-12). Torque-free, so the reference is the exact solution.
TEST(DopriTolerance, THandleGlobalErrorWithinAHundredTolerances) {
  const testing::BenchSceneBody scene = testing::t_handle_flip_body();
  const TorqueFreeMotion exact(scene.body.moments, scene.initial.orientation,
                               Eigen::Vector3d(0.05, 10.0, 0.05));
  ASSERT_EQ(exact.regime(), TorqueFreeMotion::Regime::kAboutLargestAxis);
  std::size_t previous_evaluations = 0;
  for (const double tolerance : kBenchTolerances) {
    const ToleranceRun run =
        run_against(scene, tolerance, [&](double t) { return exact.at(t).orientation; });
    std::printf("[ dopri t-handle ] tol %g: error %.3g rad = %.3g tol, %zu evaluations\n",
                tolerance, run.worst, run.worst / tolerance, run.counts.evaluations);
    EXPECT_LE(run.worst, 100.0 * tolerance) << tolerance;
    EXPECT_GT(run.worst, 0.0);
    EXPECT_GT(run.counts.evaluations, previous_evaluations);
    previous_evaluations = run.counts.evaluations;
  }
}

// The heavy top: a Lagrange top, whose exact solution is the reference. Spinning at 120 rad/s
// for 10 s (1200 rad), the errors of its ~3e3 to ~5e4 steps add up to 60 to 100 times the
// tolerance. At 1e-4 the controller alone would turn it by 1.1 rad a step, where the 5th-order
// solution is hardly better than the 4th-order one the estimate measures, and the sum was 457
// tolerances; the turn per step is capped at 0.5 rad (engine/PHYSICS.md §3).
TEST(DopriTolerance, HeavyTopGlobalErrorWithinAHundredTolerances) {
  const testing::BenchSceneBody scene = testing::heavy_top_body();
  const LagrangeTop exact(scene.body, scene.initial);
  ASSERT_EQ(exact.regime(), LagrangeTop::Regime::kNutating);
  for (const double tolerance : kBenchTolerances) {
    const ToleranceRun run =
        run_against(scene, tolerance, [&](double t) { return exact.at(t).orientation; });
    std::printf("[ dopri heavy top ] tol %g: error %.3g rad = %.3g tol, %zu evaluations\n",
                tolerance, run.worst, run.worst / tolerance, run.counts.evaluations);
    EXPECT_LE(run.worst, 100.0 * tolerance) << tolerance;
    EXPECT_GE(run.worst, tolerance) << tolerance;  // the sum of its many steps' errors
  }
}

// The turn per step is capped: a sphere spun at 10 rad/s for 10 s (a smooth motion whose
// error estimate alone would allow longer steps at a loose tolerance) takes at least 100 rad /
// 0.5 rad steps, and hardly more.
TEST(DopriTolerance, StepsTurnAtMostHalfARadian) {
  BodyModel sphere;
  sphere.moments = Eigen::Vector3d::Constant(2.0);
  const BodyState start =
      spinning_state(sphere, Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.0, 6.0, 8.0));
  StepSettings loose;
  loose.tolerance = 1e-2;
  const auto stepper = make_stepper(IntegratorKind::kDopri, sphere, start, loose);
  BodyState s = start;
  stepper->step(s, 0.0, 10.0);
  const StepCounts counts = *stepper->counts();
  EXPECT_GE(counts.accepted, 200u);
  EXPECT_LE(counts.accepted, 204u);  // the first steps, from 0.01 rad, grow 5x a step
  EXPECT_EQ(counts.rejected, 0u);
  // Still accurate: about the fixed axis the exact orientation is exp(10 s w).
  const Eigen::Quaterniond exact(Eigen::AngleAxisd(100.0, Eigen::Vector3d(0.0, 0.6, 0.8)));
  EXPECT_LE(orientation_angle(s.orientation, exact), 100 * loose.tolerance);
}

/// A free body of `scale` times (1, 2, 3) kg m^2 under a body-frame torque of `scale` times
/// (0.1, 0.2, -0.1) N m, spun at (0.4, 0.8, 0.6) rad/s: its orientation and w do not depend on
/// the scale, its L is proportional to it.
struct ScaledRotor {
  BodyModel body;
  BodyState start;
};
ScaledRotor scaled_rotor(double scale) {
  ScaledRotor rotor;
  rotor.body.moments = scale * Eigen::Vector3d(1.0, 2.0, 3.0);
  rotor.body.forces = {ConstantTorque{scale * Eigen::Vector3d(0.1, 0.2, -0.1), true}};
  rotor.start =
      spinning_state(rotor.body, Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.4, 0.8, 0.6));
  return rotor;
}

/// A body of `scale` kg on a spring of `scale` * 4 N/m from the origin to its centre of mass (no
/// torque), started at scale * (1, 0, 0) m with scale * (0, 0.5, 0) m/s: x(t) = x0 cos 2t +
/// v0 / 2 sin 2t. Positions and velocities proportional to the scale.
ScaledRotor scaled_oscillator(double scale) {
  ScaledRotor oscillator;
  oscillator.body.mass = 1.0;
  oscillator.body.forces = {Spring{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), 4.0, 0.0}};
  oscillator.start.position = scale * Eigen::Vector3d(1.0, 0.0, 0.0);
  oscillator.start.velocity = scale * Eigen::Vector3d(0.0, 0.5, 0.0);
  return oscillator;
}

/// Runs dopri over `duration` in one output step; the counts and the final state.
StepCounts run_dopri(const ScaledRotor& system, double duration, const StepSettings& settings,
                     BodyState* end = nullptr) {
  const auto stepper = make_stepper(IntegratorKind::kDopri, system.body, system.start, settings);
  BodyState s = system.start;
  stepper->step(s, 0.0, duration);
  if (end) *end = s;
  return *stepper->counts();
}

StepSettings tolerances(double relative, double absolute) {
  StepSettings settings;
  settings.tolerance = relative;
  settings.absolute_tolerance = absolute;
  return settings;
}

// The relative tolerance holds L to rtol |L| and x, v to rtol |x|, rtol |v|: a body scaled down
// by 2^-20 (exact in binary) takes exactly the same steps. Under the former norm, tol (1 +
// |y_i|), a small body's L and position were held to an absolute 1e-10 instead.
TEST(DopriTolerance, RelativeToleranceScalesEachQuantityBySize) {
  const double tiny = std::ldexp(1.0, -20);
  for (const bool rotor : {true, false}) {
    const ScaledRotor big = rotor ? scaled_rotor(1.0) : scaled_oscillator(1.0);
    const ScaledRotor small = rotor ? scaled_rotor(tiny) : scaled_oscillator(tiny);
    BodyState big_end, small_end;
    const StepCounts big_counts = run_dopri(big, 5.0, tolerances(1e-8, 0.0), &big_end);
    const StepCounts small_counts = run_dopri(small, 5.0, tolerances(1e-8, 0.0), &small_end);
    EXPECT_EQ(big_counts.accepted, small_counts.accepted) << rotor;
    EXPECT_EQ(big_counts.rejected, small_counts.rejected) << rotor;
    EXPECT_EQ(small_end.angular_momentum, tiny * big_end.angular_momentum) << rotor;
    EXPECT_EQ(small_end.position, tiny * big_end.position) << rotor;
    // And the relative tolerance is honoured: a tighter one takes more steps.
    EXPECT_GT(run_dopri(big, 5.0, tolerances(1e-10, 0.0)).accepted, big_counts.accepted + 10);
  }
}

// The oscillator's error against its closed form, relative to its amplitude, follows the
// relative tolerance; the absolute tolerance, in metres, loosens the small oscillation only.
TEST(DopriTolerance, AbsoluteToleranceLoosensOnlyWhatIsBelowIt) {
  const double tiny = std::ldexp(1.0, -20);  // ~1e-6 m of amplitude
  const double duration = 5.0;
  const Eigen::Vector3d exact = Eigen::Vector3d(1.0, 0.0, 0.0) * std::cos(2.0 * duration) +
                                Eigen::Vector3d(0.0, 0.5, 0.0) / 2.0 * std::sin(2.0 * duration);
  BodyState end;
  std::vector<double> errors;
  for (const double rtol : {1e-6, 1e-8, 1e-10}) {
    run_dopri(scaled_oscillator(1.0), duration, tolerances(rtol, 0.0), &end);
    errors.push_back((end.position - exact).norm());
    EXPECT_LE(errors.back(), 100.0 * rtol) << rtol;
  }
  EXPECT_LT(errors[1], 0.03 * errors[0]);
  EXPECT_LT(errors[2], 0.03 * errors[1]);

  const StepCounts tight = run_dopri(scaled_oscillator(tiny), duration, tolerances(1e-10, 0.0));
  const StepCounts loose =
      run_dopri(scaled_oscillator(tiny), duration, tolerances(1e-10, 1e-12), &end);
  EXPECT_LT(loose.accepted, tight.accepted / 2);
  // Loose to about atol: 1e-12 m per step.
  EXPECT_LE((end.position - tiny * exact).norm(), 1e-9);
  EXPECT_GT((end.position - tiny * exact).norm(), 1e-14);
  // The same atol leaves the 1 m oscillation's steps alone (rtol |x| = 1e-10 m dominates)...
  const StepCounts big = run_dopri(scaled_oscillator(1.0), duration, tolerances(1e-10, 1e-12));
  EXPECT_LE(big.accepted, tight.accepted + 1);
  EXPECT_GE(big.accepted + 1, tight.accepted);
  // ...and tightening it takes the small one back to the relative steps.
  const StepCounts tighter = run_dopri(scaled_oscillator(tiny), duration, tolerances(1e-10, 1e-20));
  EXPECT_GE(tighter.accepted + 1, tight.accepted);
}

TEST(DopriTolerance, BadTolerancesAreRefusedNamingTheField) {
  const ScaledRotor rotor = scaled_rotor(1.0);
  const auto problem = [&](double relative, double absolute) {
    return testing::input_error_of([&] {
      make_stepper(IntegratorKind::kDopri, rotor.body, rotor.start, tolerances(relative, absolute));
    });
  };
  EXPECT_THAT(problem(0.0, 0.0),
              HasSubstr("tolerance: expected a positive finite relative tolerance, got 0"));
  EXPECT_THAT(problem(-1e-6, 0.0), HasSubstr("tolerance: expected a positive finite"));
  EXPECT_THAT(problem(std::numeric_limits<double>::quiet_NaN(), 0.0),
              HasSubstr("tolerance: expected a positive finite relative tolerance, got nan"));
  EXPECT_THAT(problem(std::numeric_limits<double>::infinity(), 0.0),
              HasSubstr("tolerance: expected a positive finite"));
  EXPECT_THAT(
      problem(1e-8, -1e-9),
      HasSubstr("absolute_tolerance: expected a finite absolute tolerance >= 0, got -1e-09"));
  EXPECT_THAT(problem(1e-8, std::numeric_limits<double>::infinity()),
              HasSubstr("absolute_tolerance: expected a finite absolute tolerance >= 0, got inf"));
  // Fixed-step integrators take no tolerance and ignore it.
  EXPECT_NO_THROW(
      make_stepper(IntegratorKind::kRk4, rotor.body, rotor.start, tolerances(0.0, -1.0)));
}

}  // namespace
}  // namespace tumble::engine
