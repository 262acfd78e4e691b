// Rounding over long runs (engine/PHYSICS.md §3, "Rounding"): once truncation is below
// rounding, a smaller step must not make an integrator worse. Oracles: the exact torque-free
// solution of §4 evaluated at each time from the initial state, a single exponential map for a
// composition of equal turns, and cos(x) - 1 = -2 sin^2(x/2) in long double. Quantities that
// must be computed below double rounding (|q|^2 - 1) are summed with std::fma, exactly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "compensated_orientation.hpp"
#include "engine/body/rigid_body.hpp"
#include "engine/dynamics/integrators.hpp"
#include "engine/exact/torque_free_exact.hpp"
#include "engine/simulation/simulation.hpp"

namespace tumble::engine {
namespace {

using K = IntegratorKind;

// The principal moments of assets/meshes/t_handle.obj at 1000 kg/m^3 (`tumble inspect`).
const Eigen::Vector3d kTHandleMoments(4.280062e-06, 5.566125e-06, 9.576361e-06);

/// |q|^2 - 1 to far below double rounding: every square split exactly by fma, summed with
/// the rounding errors of the additions kept (TwoSum).
double norm_squared_excess(const Eigen::Quaterniond& q) {
  double sum = -1.0;
  double tail = 0.0;
  for (int i = 0; i < 4; ++i) {
    const double c = q.coeffs()[i];
    const double square = c * c;
    tail += std::fma(c, c, -square);
    const double next = sum + square;
    const double b_part = next - sum;
    tail += (sum - (next - b_part)) + (square - b_part);
    sum = next;
  }
  return sum + tail;
}

/// Largest orientation error against the exact solution over a run, sampled every 0.01 s.
double max_orientation_error(K kind, const BodyModel& body, const BodyState& start, double dt,
                             double duration) {
  SimulationSettings settings;
  settings.integrator = kind;
  settings.dt = dt;
  settings.duration = duration;
  Simulation simulation({body}, {start}, settings);
  const TorqueFreeMotion exact(
      body.moments, start.orientation,
      (start.orientation.conjugate() * start.angular_momentum).cwiseQuotient(body.moments));
  const auto every = static_cast<std::size_t>(std::lround(0.01 / dt));
  double worst = 0.0;
  while (simulation.step()) {
    if (simulation.steps() % every != 0) continue;
    const Eigen::Quaterniond reference = exact.at(simulation.time()).orientation;
    worst = std::max(worst, orientation_angle(simulation.states()[0].orientation, reference));
  }
  EXPECT_FALSE(simulation.blow_up().has_value());
  return worst;
}

// A T-handle spun near its intermediate axis, slowly enough (0.4 rad/s, 2 rad in 5 s) that
// every method's truncation error is at or below rounding already at dt 1e-2: what is left is
// rounding. Before the compensated updates the error at dt 1e-4 was 31x (free-rotor), 23x
// (splitting4) and 7x (rk4) that at 1e-2 here (6.7e-12, 1.2e-12, 1.3e-13 rad): every step
// added ~1e-16 absolute to q. Now the rounding of a step is relative to the turn it makes, and
// free-rotor continues one exact motion: at dt 1e-4 the errors are 0 (free-rotor) and 1.8e-14
// rad (splitting4, rk4), no larger than at 1e-2.
TEST(Rounding, SmallerStepsDoNotAccumulateRounding) {
  BodyModel body;
  body.name = "t-handle";
  body.mass = 0.016;
  body.moments = kTHandleMoments;
  const BodyState start =
      spinning_state(body, Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 2))),
                     Eigen::Vector3d(0.002, 0.4, 0.002));
  const double duration = 5.0;
  for (const K kind : {K::kFreeRotor, K::kSplitting4, K::kRk4, K::kExact}) {
    const double coarse = max_orientation_error(kind, body, start, 1e-2, duration);
    const double medium = max_orientation_error(kind, body, start, 1e-3, duration);
    const double fine = max_orientation_error(kind, body, start, 1e-4, duration);
    const std::string name = integrator_info(kind).name;
    // Truncation at dt 1e-2 is below rounding, so the comparison is of rounding alone.
    EXPECT_LT(coarse, 1e-13) << name;
    // A floor of a few ulps of an angle: free-rotor and exact land on the reference exactly.
    EXPECT_LE(medium, 3.0 * std::max(coarse, 1e-15)) << name << " dt 1e-3: " << medium;
    EXPECT_LE(fine, 3.0 * std::max(coarse, 1e-15)) << name << " dt 1e-4: " << fine;
  }
}

// The orientation a compensated update returns is the rounding of a quaternion that stays unit
// far below rounding: |q|^2 - 1 averages to ~0. renormalized(), one Newton step on rounded
// |q|^2, averages -5.3e-17 on the same turns: its factor 1.5 - |q|^2 / 2 falls on the coarse
// grid just above 1 (a bias that does not accumulate, since every step renormalises afresh).
// What is left here is the drift of |hi + lo|: each turn is scaled to unit length only to the
// rounding of |1 + delta|^2 - 1, ~1e-16 theta^2, which over 10^5 turns of 1.7e-3 rad averages
// ~2e-18.
TEST(CompensatedOrientation, NormalisationIsUnbiased) {
  std::mt19937_64 random(7);
  std::normal_distribution<double> normal;
  steppers::CompensatedOrientation q;
  double sum = 0.0;
  double sum_squares = 0.0;
  const int turns = 100000;
  for (int i = 0; i < turns; ++i) {
    const Eigen::Vector3d theta =
        1e-3 * Eigen::Vector3d(normal(random), normal(random), normal(random));
    q.turn_world(steppers::small_turn(theta));
    const double excess = norm_squared_excess(q.value());
    sum += excess;
    sum_squares += excess * excess;
  }
  const double mean = sum / turns;
  const double rms = std::sqrt(sum_squares / turns);
  EXPECT_GT(rms, 1e-17);  // rounded to doubles, not exact: the mean is a real average
  EXPECT_LT(rms, 2e-16);
  EXPECT_LT(std::abs(mean), 5e-18) << mean;  // 2.3e-18 measured, vs -5.3e-17
}

// 10^5 equal turns of 1e-5 rad compose to one turn of 1 rad: the compensated sum keeps the
// error of the composition at the rounding of the single exponential map (each turn's own
// relative rounding, ~1e-16 of 1e-5 rad, adds up to ~1e-16 rad), where rounding q to doubles
// every turn would add ~1e-16 rad per turn.
TEST(CompensatedOrientation, ManySmallTurnsComposeToRounding) {
  const Eigen::Vector3d axis = Eigen::Vector3d(0.3, -0.5, 0.8).normalized();
  const int turns = 100000;
  const Eigen::Vector3d theta = (1.0 / turns) * axis;
  const Eigen::Quaterniond delta = steppers::small_turn(theta);
  const Eigen::Quaterniond start(Eigen::AngleAxisd(2.0, Eigen::Vector3d(1, 0, 1).normalized()));
  steppers::CompensatedOrientation world;
  steppers::CompensatedOrientation body;
  world.resume(start);
  body.resume(start);
  for (int i = 0; i < turns; ++i) {
    world.turn_world(delta);
    body.turn_body(delta);
  }
  const Eigen::Quaterniond turn = rotation_quaternion(axis);
  EXPECT_LT(orientation_angle(world.value(), turn * start), 1e-15);
  EXPECT_LT(orientation_angle(body.value(), start * turn), 1e-15);
}

// The low part is kept only for the state the updater returned: handed another state, it
// starts from that state alone (a stepper given an edited state steps it like a new one).
TEST(CompensatedOrientation, ForgetsItsLowPartForAnotherState) {
  const Eigen::Quaterniond delta = steppers::small_turn(Eigen::Vector3d(1e-3, 0.0, 0.0));
  steppers::CompensatedOrientation used;
  for (int i = 0; i < 1000; ++i) used.turn_body(delta);
  const Eigen::Quaterniond other(Eigen::AngleAxisd(1.0, Eigen::Vector3d::UnitY()));
  used.resume(other);
  used.turn_body(delta);
  steppers::CompensatedOrientation fresh;
  fresh.resume(other);
  fresh.turn_body(delta);
  EXPECT_EQ(used.value().coeffs(), fresh.value().coeffs());
}

// cos(x) - 1 keeps its relative accuracy where 1 - cos(x) rounded near 1 would lose it all;
// both branches of half_angle (the polynomial below x^2 = 0.0025, libm above).
TEST(HalfAngle, CosMinusOneIsAccurateRelativeToItself) {
  for (const double x : {1e-9, 3e-7, 1e-4, 0.01, 0.0499, 0.0501, 0.3, 1.0, 2.5}) {
    const long double s = std::sin(0.5L * x);
    const auto expected = static_cast<double>(-2.0L * s * s);
    const HalfAngle f = half_angle(x * x);
    EXPECT_NEAR(f.cos_minus_one, expected, 4e-16 * std::abs(expected)) << x;
    EXPECT_NEAR(f.cos, 1.0 + f.cos_minus_one, 2.3e-16) << x;
  }
}

// free-rotor continues its motion only while it is handed the state it returned: an edited
// state is stepped exactly as a fresh stepper would step it.
TEST(FreeRotor, StartsOverFromAnEditedState) {
  BodyModel body;
  body.moments = kTHandleMoments;
  const BodyState start =
      spinning_state(body, Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.05, 10.0, 0.05));
  BodyState s = start;
  const auto stepper = make_stepper(K::kFreeRotor, body, s, {});
  for (int i = 0; i < 10; ++i) stepper->step(s, i * 1e-3, 1e-3);
  s.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitX()));
  BodyState edited = s;
  stepper->step(s, 0.01, 1e-3);
  const auto fresh = make_stepper(K::kFreeRotor, body, edited, {});
  fresh->step(edited, 0.01, 1e-3);
  EXPECT_EQ(s.orientation.coeffs(), edited.orientation.coeffs());
}

}  // namespace
}  // namespace tumble::engine
