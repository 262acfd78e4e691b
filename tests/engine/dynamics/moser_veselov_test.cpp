// moser-veselov (the discrete Moser-Veselov algorithm, Moser and Veselov 1991; McLachlan and
// Zanna 2005) against the exact torque-free solution: its measured order, and the integrals it
// keeps exactly for the free body (world L, energy, |L|); with torques, the order of the
// kick composition against a fine rk4 reference.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "engine/body/rigid_body.hpp"
#include "engine/dynamics/integrators.hpp"
#include "engine/exact/torque_free_exact.hpp"
#include "rigid_body_fixtures.hpp"

namespace tumble::engine {
namespace {

using namespace fixtures;

using K = IntegratorKind;

Eigen::Vector3d body_momentum(const BodyState& s) {
  return s.orientation.conjugate() * s.angular_momentum;
}

/// log2 of successive error ratios.
std::vector<double> orders_of(const std::vector<double>& errors) {
  std::vector<double> orders;
  for (std::size_t i = 1; i < errors.size(); ++i) {
    orders.push_back(std::log2(errors[i - 1] / errors[i]));
  }
  return orders;
}

// The plain DMV approximates the continuous flow at the same step to second order (McLachlan
// and Zanna 2005): orientation and body angular velocity errors at t = 4 s fall fourfold per
// halving of dt, on J = (1, 2, 3) (a flat body: the DMV's J = tr(I)/2 - I is singular here,
// which the quaternion form does not mind) and on a body inside the triangle inequality.
TEST(MoserVeselov, SecondOrderAgainstExactSolution) {
  for (const Eigen::Vector3d& moments :
       {Eigen::Vector3d(1.0, 2.0, 3.0), Eigen::Vector3d(1.0, 2.5, 3.3)}) {
    const Eigen::Vector3d omega0(0.4, 0.8, 0.6);
    const BodyModel body = free_body(moments);
    const BodyState start = spinning_state(body, kOrientation, omega0);
    const TorqueFreeMotion exact(moments, kOrientation, omega0);
    const TorqueFreeMotion::State ref = exact.at(4.0);
    std::vector<double> orientation_errors, omega_errors;
    for (int n = 100; n <= 800; n *= 2) {
      const BodyState end = run(K::kMoserVeselov, body, start, 4.0 / n, n);
      orientation_errors.push_back(orientation_angle(ref.orientation, end.orientation));
      omega_errors.push_back((body_momentum(end).cwiseQuotient(moments) - ref.omega_body).norm() /
                             ref.omega_body.norm());
    }
    const std::vector<double> q_orders = orders_of(orientation_errors);
    const std::vector<double> w_orders = orders_of(omega_errors);
    std::printf(
        "[ moser-veselov J=(%g,%g,%g) ] orientation errors %.3g .. %.3g, orders %.3f %.3f "
        "%.3f; omega orders %.3f %.3f %.3f\n",
        moments.x(), moments.y(), moments.z(), orientation_errors.front(),
        orientation_errors.back(), q_orders[0], q_orders[1], q_orders[2], w_orders[0], w_orders[1],
        w_orders[2]);
    for (std::size_t i = 0; i < q_orders.size(); ++i) {
      EXPECT_NEAR(q_orders[i], 2.0, 0.15);
      EXPECT_NEAR(w_orders[i], 2.0, 0.15);
    }
    EXPECT_GT(orientation_errors.back(), 1e-9);  // far above rounding
  }
  EXPECT_EQ(integrator_info(K::kMoserVeselov).order, 2);
}

// For the free body the DMV map keeps world L (untouched: exact to the bit), and the energy
// m . I^-1 m / 2 and |m| of the body momentum are integrals of the discrete map: kept to
// rounding over 10^4 steps of a tumbling body at a step where splitting's energy error is
// ~1e-4.
TEST(MoserVeselov, FreeBodyKeepsWorldMomentumAndEnergyToRounding) {
  const Eigen::Vector3d moments(1.0, 3.0, 3.5);
  const BodyModel body = free_body(moments);
  const BodyState start = spinning_state(body, kOrientation, Eigen::Vector3d(0.3, 2.0, 0.4));
  const auto energy = [&](const BodyState& s) {
    const Eigen::Vector3d m = body_momentum(s);
    return 0.5 * m.dot(m.cwiseQuotient(moments));
  };
  const double energy0 = energy(start), momentum0 = body_momentum(start).norm();
  const auto stepper = make_stepper(K::kMoserVeselov, body, start, {});
  BodyState s = start;
  double energy_drift = 0.0, momentum_drift = 0.0, splitting_energy_drift = 0.0;
  BodyState split = start;
  const auto splitting = make_stepper(K::kSplitting, body, start, {});
  const double h = 0.02;
  for (int i = 0; i < 10000; ++i) {
    stepper->step(s, i * h, h);
    splitting->step(split, i * h, h);
    energy_drift = std::max(energy_drift, std::abs(energy(s) / energy0 - 1.0));
    momentum_drift = std::max(momentum_drift, std::abs(body_momentum(s).norm() / momentum0 - 1.0));
    splitting_energy_drift =
        std::max(splitting_energy_drift, std::abs(energy(split) / energy0 - 1.0));
  }
  std::printf(
      "[ moser-veselov ] energy drift %.3g, |m| drift %.3g over 1e4 steps "
      "(splitting's energy error %.3g)\n",
      energy_drift, momentum_drift, splitting_energy_drift);
  EXPECT_TRUE(s.angular_momentum == start.angular_momentum);
  EXPECT_LT(energy_drift, 1e-12);
  EXPECT_LT(momentum_drift, 1e-12);
  EXPECT_GT(splitting_energy_drift, 1e-6);  // the step is not so small that anything keeps it
  EXPECT_GT(orientation_angle(s.orientation, start.orientation), 1e-3);  // and it moved
}

// With torques the kicks make a symmetric composition: second order on a heavy top (gravity on
// a pivoted asymmetric body), against rk4 at a 64 times finer step.
TEST(MoserVeselov, SecondOrderWithGravityTorque) {
  const BodyModel top = heavy_top(Eigen::Vector3d(1.25, 1.5, 0.5));
  const BodyState start =
      spinning_state(top, Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX())),
                     Eigen::Vector3d(0.5, 0.0, 8.0));
  const double horizon = 2.0;
  const BodyState ref = run(K::kRk4, top, start, horizon / 12800, 12800);
  std::vector<double> errors;
  for (int n = 200; n <= 1600; n *= 2) {
    const BodyState end = run(K::kMoserVeselov, top, start, horizon / n, n);
    errors.push_back(std::max(
        orientation_angle(ref.orientation, end.orientation),
        (end.angular_momentum - ref.angular_momentum).norm() / ref.angular_momentum.norm()));
  }
  const std::vector<double> orders = orders_of(errors);
  std::printf("[ moser-veselov top ] errors %.3g .. %.3g, orders %.3f %.3f %.3f\n", errors.front(),
              errors.back(), orders[0], orders[1], orders[2]);
  for (double p : orders) EXPECT_NEAR(p, 2.0, 0.2);
  EXPECT_GT(errors.back(), 1e-9);
}

}  // namespace
}  // namespace tumble::engine
