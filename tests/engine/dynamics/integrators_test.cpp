// The integrators against independent oracles: convergence orders measured from dt sweeps
// against the exact torque-free solution, conservation laws each method claims (and the ones
// it is documented to break), the intermediate-axis flip period from the complete elliptic
// integral (computed here by the AGM, not by the engine), the precession rates of a symmetric
// body and of a fast heavy top, dopri's tolerance control, and refusal of the exact solution
// for bodies with torques.
#include "engine/dynamics/integrators.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "base/errors.hpp"
#include "engine/body/rigid_body.hpp"
#include "engine/exact/torque_free_exact.hpp"
#include "engine/simulation/simulation.hpp"
#include "rigid_body_fixtures.hpp"
#include "support/input_error.hpp"

namespace tumble::engine {
namespace {

using namespace fixtures;

using ::testing::HasSubstr;
using K = IntegratorKind;

const Eigen::Vector3d kMoments(1.0, 2.0, 3.0);

/// Error against the exact solution at t: the larger of the orientation angle (rad) and the
/// relative error of the body angular velocity.
double error_against(const TorqueFreeMotion& exact, double t, const BodyModel& body,
                     const BodyState& s) {
  const TorqueFreeMotion::State ref = exact.at(t);
  return std::max(orientation_angle(ref.orientation, s.orientation),
                  (body_omega(body, s) - ref.omega_body).norm() / ref.omega_body.norm());
}

/// Complete elliptic integral of the first kind K(k) by the arithmetic-geometric mean:
/// K = pi / (2 AGM(1, sqrt(1 - k^2))). Independent of engine/elliptic.
double complete_elliptic_k(double k) {
  double a = 1.0, b = std::sqrt(1.0 - k * k);
  for (int i = 0; i < 60 && std::abs(a - b) > 1e-16 * a; ++i) {
    const double next_a = 0.5 * (a + b);
    b = std::sqrt(a * b);
    a = next_a;
  }
  return std::numbers::pi / (a + b);
}

// ---------------------------------------------------------------------------------------------
// Convergence orders on a torque-free asymmetric body.

struct OrderCase {
  IntegratorKind kind;
  double expected_order;
  int coarsest_steps;  ///< steps over the horizon for the coarsest dt of the sweep
};

class ConvergenceOrder : public ::testing::TestWithParam<OrderCase> {};

// Error at t = 4 s (a bit more than one flip) for dt = T/N, T/2N, T/4N, T/8N; the order from
// each halving is log2(e(h) / e(h/2)). The sweeps sit in the asymptotic range (checked by the
// two finest halvings agreeing) and well above rounding.
TEST_P(ConvergenceOrder, MatchesExpectedOrderFromDtSweep) {
  const OrderCase c = GetParam();
  const BodyModel body = free_body(kMoments);
  const Eigen::Vector3d omega0(0.4, 0.8, 0.6);
  const BodyState start = spinning_state(body, kOrientation, omega0);
  const TorqueFreeMotion exact(kMoments, kOrientation, omega0);
  const double horizon = 4.0;

  std::vector<double> errors;
  for (int n = c.coarsest_steps; n <= 8 * c.coarsest_steps; n *= 2) {
    const BodyState end = run(c.kind, body, start, horizon / n, n);
    errors.push_back(error_against(exact, horizon, body, end));
  }
  std::vector<double> orders;
  for (std::size_t i = 1; i < errors.size(); ++i)
    orders.push_back(std::log2(errors[i - 1] / errors[i]));
  std::string trace = integrator_info(c.kind).name + " errors:";
  char number[32];
  for (double e : errors) {
    std::snprintf(number, sizeof number, " %.3g", e);
    trace += number;
  }
  trace += " orders:";
  for (double p : orders) {
    std::snprintf(number, sizeof number, " %.3f", p);
    trace += number;
  }
  SCOPED_TRACE(trace);
  std::printf("[ order ] %s\n", trace.c_str());

  // The two finest halvings: asymptotic, within +-0.3 of the order.
  EXPECT_NEAR(orders[orders.size() - 1], c.expected_order, 0.3);
  EXPECT_NEAR(orders[orders.size() - 2], c.expected_order, 0.3);
  // Still far from rounding at the finest step.
  EXPECT_GT(errors.back(), 1e-11);
  // The catalog states the same order.
  EXPECT_EQ(integrator_info(c.kind).order, static_cast<int>(c.expected_order));
}

INSTANTIATE_TEST_SUITE_P(
    TorqueFreeAsymmetric, ConvergenceOrder,
    ::testing::Values(OrderCase{K::kExplicitEuler, 1.0, 2000},
                      OrderCase{K::kSemiImplicitEuler, 1.0, 2000},
                      OrderCase{K::kLieEuler, 1.0, 2000}, OrderCase{K::kImplicitEuler, 1.0, 2000},
                      OrderCase{K::kMidpoint, 2.0, 100}, OrderCase{K::kSplitting, 2.0, 100},
                      OrderCase{K::kMoserVeselov, 2.0, 100}, OrderCase{K::kRk4, 4.0, 25},
                      OrderCase{K::kSplitting4, 4.0, 25}),
    [](const ::testing::TestParamInfo<OrderCase>& test_info) {
      std::string name = integrator_info(test_info.param.kind).name;
      std::replace(name.begin(), name.end(), '-', '_');
      return name;
    });

// The note's update as written has no gyroscopic term: its error is a modelling error and does
// not shrink with dt (order 0).
TEST(SeedSemiImplicit, ErrorDoesNotShrinkWithDt) {
  const BodyModel body = free_body(kMoments);
  const Eigen::Vector3d omega0(0.4, 0.8, 0.6);
  const TorqueFreeMotion exact(kMoments, kOrientation, omega0);
  const BodyState start = spinning_state(body, kOrientation, omega0);
  const double horizon = 4.0;
  const double coarse = error_against(exact, horizon, body,
                                      run(K::kSeedSemiImplicit, body, start, horizon / 500, 500));
  const double fine = error_against(exact, horizon, body,
                                    run(K::kSeedSemiImplicit, body, start, horizon / 4000, 4000));
  // Eight times smaller dt, essentially the same (large) error: order ~ 0.
  EXPECT_GT(coarse, 0.1);
  EXPECT_NEAR(std::log2(coarse / fine) / 3.0, 0.0, 0.3);
  EXPECT_EQ(integrator_info(K::kSeedSemiImplicit).order, 0);
}

// The note's update keeps world omega frozen: the body turns rigidly about it, so body omega is
// constant (no flip) and world L = R J R^T w sweeps around instead of staying fixed.
TEST(SeedSemiImplicit, WorldOmegaFrozenNoFlipAndWorldMomentumSweeps) {
  const BodyModel body = free_body(kMoments);
  const Eigen::Vector3d omega0(0.4, 0.8, 0.6);  // circles the I3 axis: omega_2 flips sign
  const BodyState start = spinning_state(body, kOrientation, omega0);
  const Eigen::Vector3d world_omega0 = angular_velocity(body, start);
  const TorqueFreeMotion exact(kMoments, kOrientation, omega0);
  ASSERT_LT(exact.flip_interval(), 20.0);

  const auto stepper = make_stepper(K::kSeedSemiImplicit, body, start, {});
  BodyState s = start;
  const double h = 1e-2;
  double largest_sweep = 0.0, largest_omega_change = 0.0, smallest_omega2 = INFINITY;
  for (int i = 0; i < 2000; ++i) {  // 20 s, more than one exact flip interval
    stepper->step(s, i * h, h);
    largest_sweep = std::max(largest_sweep, (s.angular_momentum - start.angular_momentum).norm() /
                                                start.angular_momentum.norm());
    largest_omega_change =
        std::max(largest_omega_change, (angular_velocity(body, s) - world_omega0).norm());
    smallest_omega2 = std::min(smallest_omega2, body_omega(body, s).y());
  }
  std::printf("[ seed ] world L swept by up to %.0f%%, world omega changed by %.2g\n",
              100.0 * largest_sweep, largest_omega_change);
  EXPECT_GT(largest_sweep, 0.2);            // world L sweeps by tens of percent
  EXPECT_LT(largest_omega_change, 1e-12);   // world omega constant to rounding
  EXPECT_GT(smallest_omega2, 0.8 - 1e-12);  // never flips: body omega is frozen too
  EXPECT_LT(exact.at(exact.flip_interval()).omega_body.y(), -0.79);  // while the exact one flips
}

// ---------------------------------------------------------------------------------------------
// Exactness and conservation laws.

// free-rotor composes exact torque-free flows: without torques it is the exact solution.
TEST(FreeRotor, MatchesExactToRoundingOverManySteps) {
  const BodyModel body = free_body(kMoments);
  const Eigen::Vector3d omega0(0.4, 0.8, 0.6);
  const BodyState start = spinning_state(body, kOrientation, omega0);
  const TorqueFreeMotion exact(kMoments, kOrientation, omega0);
  const auto stepper = make_stepper(K::kFreeRotor, body, start, {});
  BodyState s = start;
  const double h = 0.01;
  double worst = 0.0;
  for (int i = 0; i < 2000; ++i) {
    stepper->step(s, i * h, h);
    worst = std::max(worst, error_against(exact, (i + 1) * h, body, s));
  }
  std::printf("[ free-rotor ] worst error over 2000 steps %.3g\n", worst);
  EXPECT_LT(worst, 1e-12);
  EXPECT_LT((s.angular_momentum - start.angular_momentum).norm(),
            1e-14 * start.angular_momentum.norm());
}

// The splittings never touch world L without torques; the Euler kicks and moser-veselov neither.
TEST(Splitting, WorldAngularMomentumExactOverTenThousandSteps) {
  const BodyModel body = free_body(Eigen::Vector3d(1.0, 3.0, 3.5));
  const BodyState start = spinning_state(body, kOrientation, Eigen::Vector3d(0.3, 2.0, 0.4));
  for (const K kind :
       {K::kSplitting, K::kSplitting4, K::kSemiImplicitEuler, K::kLieEuler, K::kMoserVeselov}) {
    SCOPED_TRACE(integrator_info(kind).name);
    const BodyState end = run(kind, body, start, 0.01, 10000);
    EXPECT_LE((end.angular_momentum - start.angular_momentum).norm(),
              1e-14 * start.angular_momentum.norm());
    // And the orientation did move (the body tumbled through flips).
    EXPECT_GT(orientation_angle(end.orientation, start.orientation), 1e-3);
  }
}

// Implicit midpoint keeps the quadratic invariants 2T = L_b . J^-1 L_b and |L_b|^2 exactly.
TEST(Midpoint, KeepsEnergyAndMomentumMagnitudeToRounding) {
  const BodyModel body = free_body(Eigen::Vector3d(1.0, 3.0, 3.5));
  const BodyState start = spinning_state(body, kOrientation, Eigen::Vector3d(0.3, 2.0, 0.4));
  const double energy0 = rotational_energy(body, start);
  const double momentum0 = start.angular_momentum.norm();
  const auto stepper = make_stepper(K::kMidpoint, body, start, {});
  BodyState s = start;
  double energy_drift = 0.0, momentum_drift = 0.0;
  for (int i = 0; i < 10000; ++i) {
    stepper->step(s, i * 0.02, 0.02);
    energy_drift = std::max(energy_drift, std::abs(rotational_energy(body, s) / energy0 - 1.0));
    momentum_drift =
        std::max(momentum_drift, std::abs(s.angular_momentum.norm() / momentum0 - 1.0));
  }
  std::printf("[ midpoint ] energy drift %.3g, |L| drift %.3g over 1e4 steps\n", energy_drift,
              momentum_drift);
  // Rounding only: the Newton solve stops at an update of 1e-14 of the state, so each step
  // may leave a few ulps; 1e4 steps of that stay below 1e-11 (splitting's bounded energy error
  // at this step is ~1e-4, explicit Euler's growth percent-level).
  EXPECT_LT(energy_drift, 1e-11);
  EXPECT_LT(momentum_drift, 1e-11);
  // The direction of world L is not an invariant of the method: it does move (not a no-op).
  EXPECT_GT((s.angular_momentum - start.angular_momentum).norm(), 1e-6 * momentum0);
}

// Explicit Euler on Euler's equations adds h (L_b x w) orthogonal to L_b each step, so |L| and
// the energy grow every step, by an amount that halves with dt (first order).
TEST(ExplicitEuler, EnergyGrowsEveryStep) {
  const BodyModel body = free_body(kMoments);
  const BodyState start = spinning_state(body, kOrientation, Eigen::Vector3d(0.4, 0.8, 0.6));
  const double energy0 = rotational_energy(body, start);
  std::array<double, 2> growth{};
  for (int refine = 0; refine < 2; ++refine) {
    const double h = refine == 0 ? 0.01 : 0.005;
    const int steps = refine == 0 ? 1000 : 2000;
    const auto stepper = make_stepper(K::kExplicitEuler, body, start, {});
    BodyState s = start;
    double previous = energy0;
    int increases = 0;
    for (int i = 0; i < steps; ++i) {
      stepper->step(s, i * h, h);
      const double e = rotational_energy(body, s);
      if (e > previous) ++increases;
      previous = e;
    }
    EXPECT_EQ(increases, steps);
    growth[static_cast<std::size_t>(refine)] = previous / energy0 - 1.0;
  }
  std::printf("[ explicit-euler ] energy growth over 10 s: %.4g (dt 0.01), %.4g (dt 0.005)\n",
              growth[0], growth[1]);
  EXPECT_GT(growth[0], 1e-3);
  EXPECT_NEAR(growth[0] / growth[1], 2.0, 0.3);
}

// Backward Euler on the gyroscopic term damps: energy falls every step (the documented trade).
TEST(ImplicitEuler, EnergyFallsEveryStep) {
  const BodyModel body = free_body(kMoments);
  const BodyState start = spinning_state(body, kOrientation, Eigen::Vector3d(0.4, 0.8, 0.6));
  const auto stepper = make_stepper(K::kImplicitEuler, body, start, {});
  BodyState s = start;
  double previous = rotational_energy(body, s);
  int decreases = 0;
  for (int i = 0; i < 1000; ++i) {
    stepper->step(s, i * 0.01, 0.01);
    const double e = rotational_energy(body, s);
    if (e < previous) ++decreases;
    previous = e;
  }
  EXPECT_EQ(decreases, 1000);
  EXPECT_LT(previous, rotational_energy(body, start) * (1.0 - 1e-3));
}

// ---------------------------------------------------------------------------------------------
// Rates measured from simulated runs against closed forms.

// The flip interval 2K(k)/lambda of engine/PHYSICS.md §4, with K from the AGM above, against the
// time between sign changes of the intermediate-axis body omega in an rk4 run.
TEST(IntermediateAxis, FlipIntervalMatchesEllipticFormula) {
  const BodyModel body = free_body(kMoments);
  const Eigen::Vector3d omega0(0.05, 1.0, 0.05);
  const BodyState start = spinning_state(body, kOrientation, omega0);

  // Closed form.
  const double i1 = kMoments.x(), i2 = kMoments.y(), i3 = kMoments.z();
  const double two_t = omega0.dot(kMoments.cwiseProduct(omega0));
  const double g2 = kMoments.cwiseProduct(omega0).squaredNorm();
  ASSERT_GT(g2, two_t * i2);  // circles the I3 axis
  const double lambda = std::sqrt((i3 - i2) * (g2 - two_t * i1) / (i1 * i2 * i3));
  const double k2 = (i2 - i1) * (two_t * i3 - g2) / ((i3 - i2) * (g2 - two_t * i1));
  const double expected = 2.0 * complete_elliptic_k(std::sqrt(k2)) / lambda;

  // Sign changes of omega_2, located by linear interpolation (sn is odd about its zeros, so the
  // interpolation error is O(h^3)).
  const double h = 1e-3;
  const auto stepper = make_stepper(K::kRk4, body, start, {});
  BodyState s = start;
  double previous = omega0.y();
  std::vector<double> crossings;
  for (int i = 0; i < 200000 && crossings.size() < 5; ++i) {
    stepper->step(s, i * h, h);
    const double current = body_omega(body, s).y();
    if ((current < 0.0) != (previous < 0.0)) {
      crossings.push_back(i * h + h * previous / (previous - current));
    }
    previous = current;
  }
  ASSERT_EQ(crossings.size(), 5u);
  const double measured = (crossings.back() - crossings.front()) / 4.0;
  std::printf("[ flip ] measured %.12f, 2K/lambda %.12f (k^2 = %.6f)\n", measured, expected, k2);
  // rk4 at this step and the O(h^3) interpolation leave ~1e-12; the issue asks for 1e-6.
  EXPECT_NEAR(measured / expected, 1.0, 1e-9);
  // Successive intervals agree too (not only on average).
  for (std::size_t i = 1; i < crossings.size(); ++i) {
    EXPECT_NEAR((crossings[i] - crossings[i - 1]) / expected, 1.0, 1e-9);
  }
}

/// Unwraps successive angles into a continuous function.
struct Unwrapper {
  double last = NAN;
  double total = 0.0;
  double operator()(double angle) {
    if (!std::isnan(last)) {
      double d = angle - last;
      while (d > std::numbers::pi) d -= 2.0 * std::numbers::pi;
      while (d < -std::numbers::pi) d += 2.0 * std::numbers::pi;
      total += d;
    }
    last = angle;
    return total;
  }
};

// Symmetric body I1 = I2: body omega cones about the symmetry axis at (I3 - I1)/I1 w3, and the
// symmetry axis cones about world L at G/I1 (engine/PHYSICS.md §4), both counter-clockwise.
TEST(SymmetricBody, PrecessionRatesMatchClosedForms) {
  const Eigen::Vector3d moments(1.0, 1.0, 2.0);
  const BodyModel body = free_body(moments);
  const Eigen::Vector3d omega0(0.3, 0.0, 2.0);
  const BodyState start = spinning_state(body, kOrientation, omega0);
  const Eigen::Vector3d momentum = start.angular_momentum;
  const Eigen::Vector3d l_hat = momentum.normalized();
  // An orthonormal frame (e1, e2, l_hat) to measure angles about L.
  const Eigen::Vector3d e1 = l_hat.unitOrthogonal();
  const Eigen::Vector3d e2 = l_hat.cross(e1);

  const double h = 1e-3;
  const int steps = 10000;
  const auto stepper = make_stepper(K::kRk4, body, start, {});
  BodyState s = start;
  Unwrapper body_angle, world_angle;
  body_angle(std::atan2(omega0.y(), omega0.x()));
  const Eigen::Vector3d axis0 = start.orientation * Eigen::Vector3d::UnitZ();
  world_angle(std::atan2(axis0.dot(e2), axis0.dot(e1)));
  double body_turn = 0.0, world_turn = 0.0;
  for (int i = 0; i < steps; ++i) {
    stepper->step(s, i * h, h);
    const Eigen::Vector3d w = body_omega(body, s);
    body_turn = body_angle(std::atan2(w.y(), w.x()));
    const Eigen::Vector3d axis = s.orientation * Eigen::Vector3d::UnitZ();
    world_turn = world_angle(std::atan2(axis.dot(e2), axis.dot(e1)));
  }
  const double duration = steps * h;
  const double body_rate = (moments.z() - moments.x()) / moments.x() * omega0.z();
  const double world_rate = momentum.norm() / moments.x();
  std::printf("[ symmetric ] body rate %.10f (expected %.10f), world rate %.10f (expected %.10f)\n",
              body_turn / duration, body_rate, world_turn / duration, world_rate);
  EXPECT_NEAR(body_turn / duration / body_rate, 1.0, 1e-9);
  EXPECT_NEAR(world_turn / duration / world_rate, 1.0, 1e-9);
}

// A fast heavy symmetric top on a pivot: I about the centre of mass (1, 1, 0.5) kg m^2, mass
// 1 kg, centre of mass l = 0.5 m up the symmetry axis, spin 50 rad/s, tilted 0.3 rad, released
// with no precession. Gyroscopic approximation: mean precession m g l / (I3 w3), nutation at
// I3 w3 / I1' with I1' = I1 + m l^2 about the pivot. Both corrections are O(m g l I1' /
// (I3 w3)^2) ~ 1% (measured: precession +1.0%, nutation -1.9%); the assertion allows 3%.
TEST(HeavyTop, PrecessionAndNutationRatesMatchGyroscopicApproximation) {
  const double mass = 1.0, l = 0.5, g = 9.81, spin = 50.0;
  const double i1_com = 1.0, i3 = 0.5;
  const double i1 = i1_com + mass * l * l;
  BodyModel top;
  top.name = "top";
  top.mass = mass;
  top.moments = Eigen::Vector3d(i1, i1, i3);
  top.pivoted = true;
  top.pivot = Eigen::Vector3d::Zero();
  top.center_offset = Eigen::Vector3d(0.0, 0.0, l);
  top.forces = {Gravity{Eigen::Vector3d(0.0, 0.0, -g)}};
  const double tilt = 0.3;
  const BodyState start =
      spinning_state(top, Eigen::Quaterniond(Eigen::AngleAxisd(tilt, Eigen::Vector3d::UnitX())),
                     Eigen::Vector3d(0.0, 0.0, spin));

  const double precession_expected = mass * g * l / (i3 * spin);
  const double nutation_expected = i3 * spin / i1;

  for (const K kind : {K::kRk4, K::kSplitting}) {
    SCOPED_TRACE(integrator_info(kind).name);
    const double h = 1e-3;
    const auto stepper = make_stepper(kind, top, start, {});
    BodyState s = start;
    Unwrapper azimuth;
    const Eigen::Vector3d axis0 = s.orientation * Eigen::Vector3d::UnitZ();
    azimuth(std::atan2(axis0.y(), axis0.x()));
    // Nutation: the tilt starts at its extreme, so its maxima (released with no precession the
    // axis first falls) recur once per nutation period; found by sign changes of its slope.
    std::vector<double> turning_times, turning_azimuths;
    double tilt_prev2 = tilt, tilt_prev = tilt, phi = 0.0;
    for (int i = 0; i < 20000; ++i) {
      stepper->step(s, i * h, h);
      const Eigen::Vector3d axis = s.orientation * Eigen::Vector3d::UnitZ();
      phi = azimuth(std::atan2(axis.y(), axis.x()));
      const double theta = std::acos(std::clamp(axis.z(), -1.0, 1.0));
      // tilt_prev is a local minimum (the top of the nutation, where it started).
      if (i >= 1 && tilt_prev < tilt_prev2 && tilt_prev <= theta) {
        // Parabola through the three samples for the time of the minimum.
        const double denom = tilt_prev2 - 2.0 * tilt_prev + theta;
        const double offset = denom > 0.0 ? 0.5 * (tilt_prev2 - theta) / denom : 0.0;
        turning_times.push_back((i + offset) * h);
        turning_azimuths.push_back(phi);
      }
      tilt_prev2 = tilt_prev;
      tilt_prev = theta;
    }
    ASSERT_GE(turning_times.size(), 50u);  // 20 s at ~0.3 s per nutation
    const double cycles = static_cast<double>(turning_times.size() - 1);
    const double nutation =
        2.0 * std::numbers::pi * cycles / (turning_times.back() - turning_times.front());
    // Mean precession over whole nutation cycles.
    const double precession = (turning_azimuths.back() - turning_azimuths.front()) /
                              (turning_times.back() - turning_times.front());
    std::printf(
        "[ top %s ] precession %.6f (m g l / I3 w3 = %.6f), nutation %.6f (I3 w3 / I1' = %.6f)\n",
        integrator_info(kind).name.c_str(), precession, precession_expected, nutation,
        nutation_expected);
    EXPECT_NEAR(precession / precession_expected, 1.0, 0.03);
    EXPECT_NEAR(nutation / nutation_expected, 1.0, 0.03);
    // Precession is about +z (L_z > 0 with gravity down): counter-clockwise.
    EXPECT_GT(precession, 0.0);
  }
}

// ---------------------------------------------------------------------------------------------
// dopri's tolerance control and the exact solution's refusal of torques.

TEST(Dopri, ErrorFallsWithToleranceToAboutTheTolerance) {
  const BodyModel body = free_body(kMoments);
  const Eigen::Vector3d omega0(0.4, 0.8, 0.6);
  const BodyState start = spinning_state(body, kOrientation, omega0);
  const TorqueFreeMotion exact(kMoments, kOrientation, omega0);
  const double h = 1.0;  // output steps long enough not to cap the controller's steps
  const int steps = 10;  // 10 s, several flips
  std::vector<double> errors;
  for (const double tolerance : {1e-5, 1e-7, 1e-9, 1e-11, 1e-13}) {
    errors.push_back(
        error_against(exact, steps * h, body, run(K::kDopri, body, start, h, steps, tolerance)));
  }
  std::printf("[ dopri ] errors at tol 1e-5..1e-13: %.3g %.3g %.3g %.3g %.3g\n", errors[0],
              errors[1], errors[2], errors[3], errors[4]);
  // Error proportional to the tolerance (about 40x it over 10 s of tumbling).
  for (std::size_t i = 1; i < errors.size(); ++i) EXPECT_LT(errors[i], 0.05 * errors[i - 1]);
  EXPECT_LT(errors.back(), 1e-11);
  EXPECT_LT(errors.front(), 1e-3);
}

// Dense output: dopri takes its own steps and interpolates the output instants (Hairer,
// Norsett, Wanner 1993, II.6), so the output step changes neither the steps nor the accuracy.
TEST(Dopri, DenseOutputIsAccurateAndLeavesTheStepsAlone) {
  const BodyModel body = free_body(kMoments);
  const Eigen::Vector3d omega0(0.4, 0.8, 0.6);
  const BodyState start = spinning_state(body, kOrientation, omega0);
  const TorqueFreeMotion exact(kMoments, kOrientation, omega0);
  const double tolerance = 1e-9, duration = 4.0;
  StepSettings settings;
  settings.tolerance = tolerance;
  std::vector<StepCounts> counts;
  for (const double h : {0.1, 0.01, 4.0}) {
    const auto stepper = make_stepper(K::kDopri, body, start, settings);
    BodyState s = start;
    double worst = 0.0;
    const int steps = static_cast<int>(std::lround(duration / h));
    for (int i = 0; i < steps; ++i) {
      stepper->step(s, i * h, h);
      worst = std::max(worst, error_against(exact, (i + 1) * h, body, s));
      EXPECT_NEAR(s.orientation.norm(), 1.0, 1e-15);  // q renormalised after interpolation
    }
    std::printf("[ dopri ] output step %g: worst error %.3g, steps %zu + %zu rejected\n", h, worst,
                stepper->counts()->accepted, stepper->counts()->rejected);
    // About the tolerance at every output instant (the interpolant is 4th order, the step 5th).
    EXPECT_LT(worst, 100.0 * tolerance) << h;
    EXPECT_GT(worst, 0.0);
    ASSERT_TRUE(stepper->counts().has_value());
    counts.push_back(*stepper->counts());
    // First same as last: one evaluation to start, then six per attempt, and (a torque-free
    // body) one after each accepted step whose energy was restored, which turns q.
    const std::size_t attempts = counts.back().accepted + counts.back().rejected;
    EXPECT_GT(counts.back().evaluations, 1 + 6 * attempts);
    EXPECT_LE(counts.back().evaluations, 1 + 6 * attempts + counts.back().accepted);
  }
  // The step sequence is the controller's alone (at most a step more to cover a later end).
  EXPECT_GT(counts[0].accepted, 20u);
  EXPECT_LE(counts[0].accepted, counts[1].accepted + 1);
  EXPECT_LE(counts[1].accepted, counts[0].accepted + 1);
  EXPECT_LE(counts[0].accepted, counts[2].accepted + 1);
  EXPECT_LE(counts[2].accepted, counts[0].accepted + 1);
}

// A state changed between calls (not what the stepper handed back) restarts the integration
// from it instead of carrying on from the stepper's own state ahead of it.
TEST(Dopri, AStateChangedFromOutsideIsTakenUp) {
  const BodyModel body = free_body(kMoments);
  const Eigen::Vector3d omega0(0.4, 0.8, 0.6), omega1(0.1, -0.3, 0.9);
  const BodyState start = spinning_state(body, kOrientation, omega0);
  const auto stepper = make_stepper(K::kDopri, body, start, {});
  BodyState s = start;
  stepper->step(s, 0.0, 0.1);
  s = spinning_state(body, kOrientation, omega1);  // replaced at t = 0.1
  stepper->step(s, 0.1, 0.5);
  const TorqueFreeMotion exact(kMoments, kOrientation, omega1);
  EXPECT_LT(error_against(exact, 0.5, body, s), 1e-8);
}

// In a Simulation a pivoted body's x and v are rewritten after every step (derived from q and
// L): dopri must carry on from its own state, not restart each output step (a restart costs
// an evaluation: evaluations = 1 + 6 attempts holds only without restarts), and its steps must
// not depend on the output step.
TEST(Dopri, APivotedTopInASimulationKeepsItsOwnSteps) {
  const BodyModel top = heavy_top(Eigen::Vector3d(1.25, 1.25, 0.5));
  const BodyState start =
      spinning_state(top, Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX())),
                     Eigen::Vector3d(0.0, 0.0, 20.0));
  std::vector<StepCounts> counts;
  std::vector<BodyState> ends;
  for (const double dt : {0.1, 0.01}) {
    SimulationSettings settings;
    settings.integrator = K::kDopri;
    settings.dt = dt;
    settings.duration = 1.0;
    settings.tolerance = 1e-9;
    Simulation simulation({top}, {start}, settings);
    while (simulation.step()) {
    }
    ASSERT_FALSE(simulation.blow_up().has_value());
    counts.push_back(simulation.step_counts());
    ends.push_back(simulation.states()[0]);
    EXPECT_EQ(counts.back().evaluations, 1 + 6 * (counts.back().accepted + counts.back().rejected));
  }
  EXPECT_LE(counts[0].accepted, counts[1].accepted + 1);
  EXPECT_LE(counts[1].accepted, counts[0].accepted + 1);
  EXPECT_GT(counts[0].accepted, 20u);
  // The same trajectory, sampled differently: the end states agree to about the tolerance.
  EXPECT_LT(orientation_angle(ends[0].orientation, ends[1].orientation), 1e-7);
}

TEST(Exact, RefusesBodiesWithTorques) {
  BodyModel torqued = free_body(kMoments);
  torqued.name = "spinner";
  torqued.forces = {ConstantTorque{Eigen::Vector3d(0.0, 0.0, 1.0), false}};
  BodyModel top = heavy_top(kMoments);
  BodyModel sprung = free_body(kMoments);
  sprung.name = "sprung";
  sprung.forces = {Spring{Eigen::Vector3d::Zero(), Eigen::Vector3d(0.1, 0.0, 0.0), 10.0, 0.0}};
  for (const BodyModel* body : {&torqued, &top, &sprung}) {
    SCOPED_TRACE(body->name);
    EXPECT_FALSE(body->torque_free());
    const std::string message = tumble::testing::input_error_of(
        [&] { make_stepper(K::kExact, *body, BodyState{}, {}); }, "a body with a torque");
    EXPECT_THAT(message, HasSubstr("torque-free"));
    EXPECT_THAT(message, HasSubstr(body->name));
  }
  // Gravity on a free body acts at the centre of mass: no torque, exact accepts it.
  BodyModel falling = free_body(kMoments);
  falling.forces = {Gravity{Eigen::Vector3d(0.0, 0.0, -9.81)}};
  EXPECT_TRUE(falling.torque_free());
  EXPECT_NO_THROW(make_stepper(K::kExact, falling, BodyState{}, {}));
}

// "Leave out what the scene does not need": a body with an empty force list is torque-free and
// conservative (so the exact solution and the energy check apply to it), and its step path
// skips the force code. What we can assert without instrumenting the engine: adding a term that
// contributes nothing (zero gravity) changes no bit of any integrator's result, so skipping the
// force code for an empty list is a pure saving, not a change of scheme. (The saving itself is
// measured in bench_integrators: BM_Step vs BM_StepForced.)
TEST(ForceTerms, EmptyListBehavesAsZeroGravityForEveryIntegrator) {
  BodyModel bare = free_body(kMoments);
  EXPECT_TRUE(bare.forces.empty());
  EXPECT_TRUE(bare.torque_free());
  EXPECT_TRUE(bare.conservative());
  BodyModel zero_gravity = bare;
  zero_gravity.forces = {Gravity{Eigen::Vector3d::Zero()}};
  BodyState start = spinning_state(bare, kOrientation, Eigen::Vector3d(0.4, 0.8, 0.6));
  start.position = Eigen::Vector3d(1.0, 2.0, 3.0);
  start.velocity = Eigen::Vector3d(0.5, -0.25, 0.125);
  for (const IntegratorInfo& info : integrator_catalog()) {
    SCOPED_TRACE(info.name);
    const BodyState a = run(info.kind, bare, start, 0.01, 200);
    const BodyState b = run(info.kind, zero_gravity, start, 0.01, 200);
    EXPECT_TRUE(a.position == b.position);
    EXPECT_TRUE(a.velocity == b.velocity);
    EXPECT_TRUE(a.orientation.coeffs() == b.orientation.coeffs());
    EXPECT_TRUE(a.angular_momentum == b.angular_momentum);
    // And the free flight is exact for every method: x = x0 + v0 t (v is never touched).
    EXPECT_TRUE(a.velocity == start.velocity);
    EXPECT_LT((a.position - (start.position + 2.0 * start.velocity)).norm(), 1e-13);
  }
}

}  // namespace
}  // namespace tumble::engine
