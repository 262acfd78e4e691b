// The implicit midpoint rule solved by Newton: its analytic Jacobian against central finite
// differences of the right-hand side, the stiff spring of engine/PHYSICS.md §7 far beyond the
// fixed-point limit h |df/dy| = 2 against the rule's closed-form phase (energy kept to
// rounding), and order 2 on a damped, forced body against dopri.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "engine/body/rigid_body.hpp"
#include "engine/dynamics/integrators.hpp"
#include "engine/simulation/reference_motion.hpp"
#include "engine/simulation/simulation.hpp"

// The right-hand side and its Jacobian, private to the engine.
#include "implicit_midpoint.hpp"

namespace tumble::engine {
namespace {

using K = IntegratorKind;
namespace rule = steppers::implicit_midpoint;

const Eigen::Quaterniond kOrientation(Eigen::AngleAxisd(0.7,
                                                        Eigen::Vector3d(1, 2, 3).normalized()));

/// Every force term the Jacobian knows, on a free or a pivoted body.
BodyModel forced_body(bool pivoted) {
  BodyModel body;
  body.name = pivoted ? "forced top" : "forced";
  body.mass = 1.5;
  body.moments = Eigen::Vector3d(1.0, 2.0, 2.5);
  body.pivoted = pivoted;
  body.pivot = Eigen::Vector3d(0.1, -0.2, 0.3);
  body.center_offset = Eigen::Vector3d(0.05, -0.1, 0.4);
  body.forces = {Gravity{Eigen::Vector3d(0.3, -0.2, -9.81)},
                 Spring{Eigen::Vector3d(0.2, -0.1, 1.0), Eigen::Vector3d(0.3, -0.2, 0.1), 6.0, 2.4},
                 Spring{Eigen::Vector3d(-0.5, 0.4, 0.0), Eigen::Vector3d(-0.1, 0.3, 0.2), 2.0, 0.0},
                 ConstantTorque{Eigen::Vector3d(0.2, -0.1, 0.3), true},
                 ConstantTorque{Eigen::Vector3d(-0.1, 0.15, 0.05), false}};
  return body;
}

// Central differences, step 1e-6 per component: truncation ~1e-12 |f'''|, rounding
// ~1e-16 |f| / 1e-6 = 1e-10; the analytic Jacobian must agree to 1e-7 of its largest entry.
TEST(MidpointNewton, JacobianMatchesFiniteDifferences) {
  for (const bool pivoted : {false, true}) {
    SCOPED_TRACE(pivoted ? "pivoted" : "free");
    const BodyModel body = forced_body(pivoted);
    BodyState s = spinning_state(body, kOrientation, Eigen::Vector3d(0.4, -0.8, 1.6));
    s.position = Eigen::Vector3d(0.6, 0.2, 0.5);
    s.velocity = Eigen::Vector3d(0.1, -0.3, 0.2);
    rule::Vector13 y = rule::pack(s);
    y.segment<4>(6) *= 1.1;  // off the unit sphere: the normalisation's derivative counts
    const rule::Matrix13 analytic = rule::rate_jacobian(body, y);
    rule::Matrix13 numeric;
    for (int j = 0; j < 13; ++j) {
      const double step = 1e-6;
      rule::Vector13 up = y, down = y;
      up[j] += step;
      down[j] -= step;
      numeric.col(j) = (rule::rate(body, up) - rule::rate(body, down)) / (2.0 * step);
    }
    const double largest = analytic.cwiseAbs().maxCoeff();
    const double worst = (analytic - numeric).cwiseAbs().maxCoeff();
    std::printf("[ midpoint jacobian ] %s: largest entry %.3g, worst difference %.3g\n",
                pivoted ? "pivoted" : "free", largest, worst);
    EXPECT_GT(largest, 1.0);
    EXPECT_LT(worst, 1e-7 * largest);
    // Every block the forces fill is exercised (not zero by accident).
    const auto block_norm = [&](int row, int col, int rows, int cols) {
      return analytic.block(row, col, rows, cols).norm();
    };
    EXPECT_GT(block_norm(10, 6, 3, 4), 0.1);   // torque against orientation
    EXPECT_GT(block_norm(10, 10, 3, 3), 0.1);  // torque against L_b
    if (!pivoted) {
      EXPECT_GT(block_norm(3, 6, 3, 4), 0.1);  // force against q
    }
  }
}

// The stiff-spring body of engine/PHYSICS.md §7: a 2 kg bob on an 8 N/m undamped spring at its
// centre (wn = 2 rad/s), released at rest 0.5 m from the anchor. The midpoint rule on the
// oscillator is the Cayley transform: each step turns the phase by 2 atan(wn h / 2), so after n
// steps the offset is 0.5 cos(n 2 atan(wn h / 2)), and the energy is an exact invariant. The
// fixed-point solve failed beyond wn h = 2; Newton solves the linear stage at any step.
TEST(MidpointNewton, StiffSpringHeldToHundredTimesTheFixedPointLimit) {
  BodyModel bob;
  bob.name = "stiff-spring";
  bob.mass = 2.0;
  bob.moments = Eigen::Vector3d::Constant(1e-3);
  const Eigen::Vector3d anchor(0.0, 0.0, 1.0);
  bob.forces = {Spring{anchor, Eigen::Vector3d::Zero(), 8.0, 0.0}};
  BodyState start;
  start.position = Eigen::Vector3d(0.5, 0.0, 1.0);
  const double wn = 2.0;
  for (const double wn_h : {1.0, 10.0, 100.0}) {
    SCOPED_TRACE(wn_h);
    const int steps = 200;
    const double dt = wn_h / wn;
    SimulationSettings settings;
    settings.integrator = K::kMidpoint;
    settings.dt = dt;
    settings.duration = steps * dt;
    Simulation sim({bob}, {start}, settings);
    const double energy0 = energy(bob, sim.states()[0]);
    double worst = 0.0;
    while (sim.step()) {
      worst = std::max(worst, std::abs(energy(bob, sim.states()[0]) - energy0) / energy0);
    }
    ASSERT_FALSE(sim.blow_up().has_value());
    EXPECT_EQ(sim.steps(), static_cast<std::size_t>(steps));
    const double phase = steps * 2.0 * std::atan(0.5 * wn_h);
    const Eigen::Vector3d offset = sim.states()[0].position - anchor;
    std::printf("[ midpoint stiff ] wn dt %g: energy drift %.3g, offset error %.3g\n", wn_h, worst,
                std::abs(offset.x() - 0.5 * std::cos(phase)));
    EXPECT_LT(worst, 1e-12);
    EXPECT_NEAR(offset.x(), 0.5 * std::cos(phase), 1e-11);
    EXPECT_LT(offset.tail<2>().norm(), 1e-15);
  }
}

// Without a spring the translation decouples from the rotation and is solved on its own: under
// gravity the rule is exact for the constant acceleration, x = x0 + v0 t + g t^2 / 2, whatever
// the torques do to the rotation.
TEST(MidpointNewton, FreeFallIsExactBesideTheTorques) {
  BodyModel body = forced_body(false);
  body.forces.erase(body.forces.begin() + 1, body.forces.begin() + 3);  // the springs
  const Eigen::Vector3d g = std::get<Gravity>(body.forces[0]).acceleration;
  BodyState start = spinning_state(body, kOrientation, Eigen::Vector3d(0.4, -0.8, 1.6));
  start.position = Eigen::Vector3d(0.6, 0.2, 0.5);
  start.velocity = Eigen::Vector3d(0.1, -0.3, 2.0);
  SimulationSettings settings;
  settings.integrator = K::kMidpoint;
  settings.dt = 0.05;
  settings.duration = 2.0;
  Simulation sim({body}, {start}, settings);
  while (!sim.finished()) sim.step();
  ASSERT_FALSE(sim.blow_up().has_value());
  const double t = sim.time();
  const BodyState& s = sim.states()[0];
  EXPECT_LT((s.position - (start.position + t * start.velocity + 0.5 * t * t * g)).norm(), 1e-12);
  EXPECT_LT((s.velocity - (start.velocity + t * g)).norm(), 1e-12);
  EXPECT_GT(orientation_angle(s.orientation, start.orientation), 0.1);
}

// Order 2 with every kind of force (damped springs, torques, gravity) on a free and a pivoted
// body, against dopri at engine::kReferenceTolerance; the error is the larger of the
// orientation angle and the relative error of world L.
TEST(MidpointNewton, SecondOrderWithForcesAgainstDopri) {
  const double horizon = 2.0;
  for (const bool pivoted : {false, true}) {
    SCOPED_TRACE(pivoted ? "pivoted" : "free");
    const BodyModel body = forced_body(pivoted);
    BodyState start = spinning_state(body, kOrientation, Eigen::Vector3d(0.4, -0.8, 1.6));
    start.position = Eigen::Vector3d(0.6, 0.2, 0.5);
    const BodyState ref = ReferenceMotion({body}, {start}).at(horizon)[0];
    std::vector<double> errors;
    for (int n = 20; n <= 160; n *= 2) {
      SimulationSettings settings;
      settings.integrator = K::kMidpoint;
      settings.dt = horizon / n;
      settings.duration = horizon;
      Simulation sim({body}, {start}, settings);
      while (!sim.finished()) sim.step();
      ASSERT_FALSE(sim.blow_up().has_value());
      const BodyState& s = sim.states()[0];
      errors.push_back(std::max(
          orientation_angle(s.orientation, ref.orientation),
          (s.angular_momentum - ref.angular_momentum).norm() / ref.angular_momentum.norm()));
    }
    for (std::size_t i = 1; i < errors.size(); ++i) {
      const double order = std::log2(errors[i - 1] / errors[i]);
      std::printf("[ midpoint order ] %s: %.3g -> %.3g, order %.3f\n", pivoted ? "pivoted" : "free",
                  errors[i - 1], errors[i], order);
      EXPECT_NEAR(order, 2.0, 0.3);
    }
    EXPECT_GT(errors.back(), 1e-9);
  }
}

}  // namespace
}  // namespace tumble::engine
