// Convergence orders of the splitting family with velocity-dependent forces: a damped spring
// attached off the centre of mass (so the damping exerts a force and a torque), with and
// without an extra constant torque, on a free body and on a pivoted top under gravity. The
// reference is dopri at engine::kReferenceTolerance (engine::ReferenceMotion); the error is the
// one `tumble bench` reports, the larger of the orientation angle and the relative errors of
// world L and v. The kick of the damped terms is the exact flow of the linear ODE it is for
// frozen x and q (engine/PHYSICS.md §3), so the orders are those of the conservative case.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "engine/body/rigid_body.hpp"
#include "engine/dynamics/integrators.hpp"
#include "engine/simulation/reference_motion.hpp"
#include "engine/simulation/simulation.hpp"

// The kick itself, private to the engine.
#include "damped_kick.hpp"

namespace tumble::engine {
namespace {

using K = IntegratorKind;

const Eigen::Quaterniond kOrientation(Eigen::AngleAxisd(0.7,
                                                        Eigen::Vector3d(1, 2, 3).normalized()));

/// A free body (1, 2, 3) tumbling at about 1 rad/s on a damped spring attached 0.37 m from
/// its centre of mass (damping ratio of the translation about 0.4).
struct DampedCase {
  std::string name;
  BodyModel body;
  BodyState start;
};

DampedCase free_case(bool with_torque) {
  DampedCase c;
  c.name = with_torque ? "free, damped spring and body torque" : "free, damped spring";
  c.body.name = "damped";
  c.body.mass = 1.5;
  c.body.moments = Eigen::Vector3d(1.0, 2.0, 3.0);
  c.body.forces = {
      Spring{Eigen::Vector3d(0.2, -0.1, 1.0), Eigen::Vector3d(0.3, -0.2, 0.1), 6.0, 2.4}};
  if (with_torque) {
    c.body.forces.push_back(ConstantTorque{Eigen::Vector3d(0.2, -0.1, 0.3), true});
    c.body.forces.push_back(ConstantTorque{Eigen::Vector3d(-0.1, 0.15, 0.05), false});
  }
  c.start = spinning_state(c.body, kOrientation, Eigen::Vector3d(0.4, 0.8, 0.6));
  c.start.position = Eigen::Vector3d(0.6, 0.2, 0.5);
  c.start.velocity = Eigen::Vector3d(0.1, -0.3, 0.2);
  return c;
}

/// A pivoted top under gravity with a damped spring on its side: the kick acts on L only.
DampedCase pivoted_case(bool with_torque) {
  DampedCase c;
  c.name = with_torque ? "pivoted, damped spring and world torque" : "pivoted, damped spring";
  c.body.name = "damped top";
  c.body.mass = 1.0;
  c.body.moments = Eigen::Vector3d(1.25, 1.25, 0.5);
  c.body.pivoted = true;
  c.body.center_offset = Eigen::Vector3d(0.0, 0.0, 0.5);
  c.body.forces = {
      Gravity{Eigen::Vector3d(0.0, 0.0, -9.81)},
      Spring{Eigen::Vector3d(0.5, 0.0, 0.4), Eigen::Vector3d(0.2, 0.0, 0.4), 3.0, 4.0}};
  if (with_torque) c.body.forces.push_back(ConstantTorque{Eigen::Vector3d(0.3, -0.2, 0.1), false});
  c.start =
      spinning_state(c.body, Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX())),
                     Eigen::Vector3d(0.5, -0.3, 4.0));
  return c;
}

/// The larger of the orientation angle (rad) and the relative errors of world L and, for a
/// free body, of v.
double error_of(const BodyModel& body, const BodyState& s, const BodyState& ref) {
  double e = orientation_angle(s.orientation, ref.orientation);
  e = std::max(e, (s.angular_momentum - ref.angular_momentum).norm() / ref.angular_momentum.norm());
  if (!body.pivoted) e = std::max(e, (s.velocity - ref.velocity).norm() / ref.velocity.norm());
  return e;
}

BodyState run_damped(const DampedCase& c, K kind, double dt, double duration) {
  SimulationSettings settings;
  settings.integrator = kind;
  settings.dt = dt;
  settings.duration = duration;
  Simulation sim({c.body}, {c.start}, settings);
  while (!sim.finished()) sim.step();
  EXPECT_FALSE(sim.blow_up().has_value());
  return sim.states()[0];
}

/// Least-squares slope of log error against log dt.
double fitted_order(const std::vector<double>& dts, const std::vector<double>& errors) {
  double mx = 0.0, my = 0.0;
  for (std::size_t i = 0; i < dts.size(); ++i) {
    mx += std::log(dts[i]);
    my += std::log(errors[i]);
  }
  const double count = static_cast<double>(dts.size());
  mx /= count;
  my /= count;
  double sxy = 0.0, sxx = 0.0;
  for (std::size_t i = 0; i < dts.size(); ++i) {
    const double dx = std::log(dts[i]) - mx;
    sxy += dx * (std::log(errors[i]) - my);
    sxx += dx * dx;
  }
  return sxy / sxx;
}

struct DampedOrderCase {
  K kind;
  double expected_order;
  int coarsest_steps;  ///< over the 2 s horizon
};

class DampedOrder : public ::testing::TestWithParam<DampedOrderCase> {};

// dt = T/N, T/2N, T/4N, T/8N over T = 2 s: the fitted slope, and the finest halving on its own,
// within +-0.3 of the order, for each of the four cases.
TEST_P(DampedOrder, MatchesTheConservativeOrder) {
  const DampedOrderCase oc = GetParam();
  const double horizon = 2.0;
  for (const DampedCase& c :
       {free_case(false), free_case(true), pivoted_case(false), pivoted_case(true)}) {
    SCOPED_TRACE(c.name);
    const ReferenceMotion reference({c.body}, {c.start});
    ASSERT_EQ(reference.kind(), ReferenceMotion::Kind::kDopri);
    const BodyState ref = reference.at(horizon)[0];
    std::vector<double> dts, errors;
    for (int n = oc.coarsest_steps; n <= 8 * oc.coarsest_steps; n *= 2) {
      dts.push_back(horizon / n);
      errors.push_back(error_of(c.body, run_damped(c, oc.kind, horizon / n, horizon), ref));
    }
    const double fit = fitted_order(dts, errors);
    const double finest = std::log2(errors[errors.size() - 2] / errors.back());
    std::printf("[ damped order ] %s, %s: errors %.3g %.3g %.3g %.3g, fitted %.3f, finest %.3f\n",
                integrator_info(oc.kind).name.c_str(), c.name.c_str(), errors[0], errors[1],
                errors[2], errors[3], fit, finest);
    EXPECT_NEAR(fit, oc.expected_order, 0.3);
    EXPECT_NEAR(finest, oc.expected_order, 0.3);
    // Far above the reference's own error at the finest step.
    EXPECT_GT(errors.back(), 1e-10);
  }
}

INSTANTIATE_TEST_SUITE_P(SplittingFamily, DampedOrder,
                         ::testing::Values(DampedOrderCase{K::kSplitting, 2.0, 16},
                                           DampedOrderCase{K::kSplitting4, 4.0, 8},
                                           DampedOrderCase{K::kFreeRotor, 2.0, 16},
                                           DampedOrderCase{K::kMoserVeselov, 2.0, 16}),
                         [](const ::testing::TestParamInfo<DampedOrderCase>& test_info) {
                           std::string name = integrator_info(test_info.param.kind).name;
                           for (char& ch : name)
                             if (ch == '-') ch = '_';
                           return name;
                         });

// The kick against closed forms. A damper at the centre of mass under gravity:
// v(t) = v_inf + (v0 - v_inf) e^(-c t / m), v_inf = m g / c, L untouched.
TEST(DampedKick, TranslationMatchesTheExponentialApproach) {
  BodyModel body;
  body.mass = 2.0;
  body.moments = Eigen::Vector3d(1.0, 2.0, 3.0);
  const double c = 3.0;
  const Eigen::Vector3d g(0.0, 0.0, -9.81);
  body.forces = {Gravity{g}, Spring{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), 0.0, c}};
  ASSERT_TRUE(steppers::has_damping(body));
  BodyState s = spinning_state(body, kOrientation, Eigen::Vector3d(0.4, 0.8, 0.6));
  s.velocity = Eigen::Vector3d(1.0, -2.0, 0.5);
  const BodyState start = s;
  for (const double t : {0.01, 0.7, -0.3}) {
    s = start;
    steppers::damped_kick(body, s, t);
    const Eigen::Vector3d v_inf = body.mass * g / c;
    const Eigen::Vector3d expected =
        v_inf + (start.velocity - v_inf) * std::exp(-c * t / body.mass);
    EXPECT_LT((s.velocity - expected).norm(), 1e-14 * expected.norm()) << t;
    EXPECT_LT((s.angular_momentum - start.angular_momentum).norm(),
              1e-15 * start.angular_momentum.norm());
  }
}

// A pivoted sphere (J = j I) with a damper at r: dL/dt = (c / j) [r]x [r]x L, so the component
// of L along r stays and the rest decays as e^(-c |r|^2 t / j).
TEST(DampedKick, PivotedSphereLosesTheMomentumAcrossTheArm) {
  BodyModel body;
  body.pivoted = true;
  const double j = 0.4, c = 1.5;
  body.moments = Eigen::Vector3d::Constant(j);
  const Eigen::Vector3d attach(0.3, -0.1, 0.2);
  body.forces = {Spring{Eigen::Vector3d(1.0, 2.0, 3.0), attach, 0.0, c}};
  BodyState s = spinning_state(body, kOrientation, Eigen::Vector3d(1.0, -0.5, 2.0));
  const BodyState start = s;
  const double t = 0.8;
  steppers::damped_kick(body, s, t);
  const Eigen::Vector3d r = start.orientation * attach;
  const Eigen::Vector3d along = r * r.dot(start.angular_momentum) / r.squaredNorm();
  const Eigen::Vector3d expected =
      along + (start.angular_momentum - along) * std::exp(-c * r.squaredNorm() * t / j);
  EXPECT_LT((s.angular_momentum - expected).norm(), 1e-14 * expected.norm());
}

// With damping close to zero the exact flow is the explicit kick of the constant forces
// (v += a t, L += tau t), which undamped bodies take directly.
TEST(DampedKick, VanishingDampingIsTheConstantKick) {
  DampedCase c = free_case(true);
  std::get<Spring>(c.body.forces[0]).damping = 1e-300;
  ASSERT_TRUE(steppers::has_damping(c.body));
  BodyState s = c.start;
  const double t = 0.05;
  steppers::damped_kick(c.body, s, t);
  const Wrench w = wrench(c.body, c.start, angular_velocity(c.body, c.start));
  EXPECT_LT((s.velocity - (c.start.velocity + t * w.force / c.body.mass)).norm(), 1e-15);
  EXPECT_LT((s.angular_momentum - (c.start.angular_momentum + t * w.torque)).norm(), 1e-15);
  std::get<Spring>(c.body.forces[0]).damping = 0.0;
  EXPECT_FALSE(steppers::has_damping(c.body));
}

// One damped spring takes the rank-3 closed form, several the matrix exponential: the same
// spring split into two at the same point (stiffness and damping halved) must give the same
// kick, free and pivoted, short and long.
TEST(DampedKick, OneSpringClosedFormMatchesTheMatrixExponential) {
  for (const DampedCase& c : {free_case(true), pivoted_case(true)}) {
    SCOPED_TRACE(c.name);
    BodyModel split = c.body;
    for (ForceTerm& term : split.forces) {
      if (auto* spring = std::get_if<Spring>(&term)) {
        spring->stiffness *= 0.5;
        spring->damping *= 0.5;
        split.forces.push_back(*spring);
        break;
      }
    }
    for (const double t : {1e-4, 0.01, -0.3, 2.0}) {
      BodyState one = c.start, two = c.start;
      steppers::damped_kick(c.body, one, t);
      steppers::damped_kick(split, two, t);
      const double scale = c.start.angular_momentum.norm() + c.start.velocity.norm();
      EXPECT_LT((one.velocity - two.velocity).norm(), 1e-14 * scale) << t;
      EXPECT_LT((one.angular_momentum - two.angular_momentum).norm(), 1e-14 * scale) << t;
      EXPECT_GT((one.angular_momentum - c.start.angular_momentum).norm(), 1e-6 * scale) << t;
    }
  }
}

// The cached flow is reused only for the same x, q and t: a kick at another orientation, or
// over another time, with the cache filled gives what a fresh kick gives, bit for bit.
TEST(DampedKick, CachedFlowOnlyForTheSameConfigurationAndTime) {
  const DampedCase c = free_case(true);
  steppers::KickFlowCache cache;
  BodyState first = c.start;
  steppers::damped_kick(c.body, first, 0.05, &cache);
  ASSERT_TRUE(cache.valid);
  BodyState turned = c.start;
  turned.orientation =
      Eigen::Quaterniond(Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitZ())) * c.start.orientation;
  for (const auto& [state, t] : {std::pair{c.start, 0.05}, std::pair{c.start, 0.04},
                                 std::pair{turned, 0.05}, std::pair{first, 0.05}}) {
    BodyState cached = state, fresh = state;
    steppers::damped_kick(c.body, cached, t, &cache);
    steppers::damped_kick(c.body, fresh, t);
    EXPECT_EQ(cached.velocity, fresh.velocity);
    EXPECT_EQ(cached.angular_momentum, fresh.angular_momentum);
  }
}

}  // namespace
}  // namespace tumble::engine
