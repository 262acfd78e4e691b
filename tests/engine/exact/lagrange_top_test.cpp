// The exact heavy symmetric top (engine/PHYSICS.md §4b) against dopri at a tight tolerance,
// the fast-top precession formula, its own invariants and closed forms of its degenerate
// motions; the predicate; the `exact` integrator and the reference built on it.
#include "engine/exact/lagrange_top.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "base/errors.hpp"
#include "engine/simulation/reference_motion.hpp"
#include "engine/simulation/simulation.hpp"

namespace {

using tumble::engine::BodyModel;
using tumble::engine::BodyState;
using tumble::engine::LagrangeTop;
using tumble::engine::orientation_angle;

constexpr double kG = 9.81;

/// The stability suite's heavy top (engine/PHYSICS.md §7): J about the pivot (1.25, 1.25, 0.5),
/// 1 kg, centre of mass 0.5 m up the axis.
BodyModel heavy_top() {
  BodyModel top;
  top.name = "top";
  top.mass = 1.0;
  top.moments = Eigen::Vector3d(1.25, 1.25, 0.5);
  top.pivoted = true;
  top.center_offset = Eigen::Vector3d(0.0, 0.0, 0.5);
  top.forces = {tumble::engine::Gravity{Eigen::Vector3d(0.0, 0.0, -kG)}};
  return top;
}

/// Spinning at `spin` about its axis, tilted by `tilt` about x.
BodyState tilted(const BodyModel& top, double tilt, const Eigen::Vector3d& omega_principal) {
  return tumble::engine::spinning_state(
      top, Eigen::Quaterniond(Eigen::AngleAxisd(tilt, Eigen::Vector3d::UnitX())), omega_principal);
}

/// dopri at 1e-13 sampled every `interval` to `duration`.
std::vector<BodyState> dopri(const BodyModel& body, const BodyState& start, double interval,
                             double duration) {
  tumble::engine::SimulationSettings settings;
  settings.integrator = tumble::engine::IntegratorKind::kDopri;
  settings.dt = interval;
  settings.duration = duration;
  settings.tolerance = 1e-13;
  settings.blowup_factor = std::numeric_limits<double>::infinity();  // E0 may be ~0
  tumble::engine::Simulation simulation({body}, {start}, settings);
  std::vector<BodyState> states;
  while (simulation.step()) states.push_back(simulation.states().front());
  return states;
}

/// Largest orientation angle and relative L difference from dopri over the samples.
struct Agreement {
  double orientation = 0.0;
  double momentum = 0.0;
};
Agreement agreement(const BodyModel& body, const BodyState& start, double interval,
                    double duration) {
  const LagrangeTop top(body, start);
  const std::vector<BodyState> reference = dopri(body, start, interval, duration);
  Agreement worst;
  for (std::size_t k = 0; k < reference.size(); ++k) {
    const BodyState exact = top.at(interval * static_cast<double>(k + 1));
    worst.orientation =
        std::max(worst.orientation, orientation_angle(exact.orientation, reference[k].orientation));
    worst.momentum =
        std::max(worst.momentum, (exact.angular_momentum - reference[k].angular_momentum).norm() /
                                     reference[k].angular_momentum.norm());
  }
  return worst;
}

TEST(LagrangeTop, AgreesWithDopriOnTheStabilityHeavyTop) {
  const BodyModel body = heavy_top();
  const BodyState start = tilted(body, 0.3, Eigen::Vector3d(0.0, 0.0, 50.0));
  const LagrangeTop top(body, start);
  ASSERT_EQ(top.regime(), LagrangeTop::Regime::kNutating);
  // A real nutation: u between two distinct roots, the top starting at the upper one.
  EXPECT_NEAR(top.u_max(), std::cos(0.3), 1e-15);
  EXPECT_GT(top.u_max() - top.u_min(), 1e-4);
  const Agreement worst = agreement(body, start, 0.25, 10.0);
  EXPECT_LT(worst.orientation, 1e-10);
  EXPECT_LT(worst.momentum, 1e-10);
}

TEST(LagrangeTop, AgreesWithDopriOnASlowWideNutationAboutAnotherAxis) {
  // Symmetric about the principal x axis (moments ascending put the distinct one first), centre
  // of mass below the pivot on -x, gravity along -y, a slow spin with a sideways push: u swings
  // over most of [-1, 1] and the precession reverses within each nutation.
  BodyModel body;
  body.name = "pendulum";
  body.mass = 2.0;
  body.moments = Eigen::Vector3d(0.3, 0.8, 0.8);
  body.pivoted = true;
  body.center_offset = Eigen::Vector3d(-0.4, 0.0, 0.0);
  body.forces = {tumble::engine::Gravity{Eigen::Vector3d(0.0, -kG, 0.0)}};
  const Eigen::Quaterniond q(Eigen::AngleAxisd(1.1, Eigen::Vector3d(0.3, 0.2, 1.0).normalized()));
  const BodyState start = tumble::engine::spinning_state(body, q, Eigen::Vector3d(6.0, 1.5, -2.0));
  const LagrangeTop top(body, start);
  ASSERT_EQ(top.regime(), LagrangeTop::Regime::kNutating);
  EXPECT_GT(top.u_max() - top.u_min(), 0.2);
  const Agreement worst = agreement(body, start, 0.25, 10.0);
  EXPECT_LT(worst.orientation, 1e-10);
  EXPECT_LT(worst.momentum, 1e-10);
}

TEST(LagrangeTop, AgreesWithDopriThroughTheVertical) {
  // Started upright with a sideways swing: u = 1 is a root, the axis passes through the
  // vertical once per nutation, where phi and psi are singular.
  const BodyModel body = heavy_top();
  const BodyState start = tumble::engine::spinning_state(body, Eigen::Quaterniond::Identity(),
                                                         Eigen::Vector3d(1.5, 0.0, 8.0));
  const LagrangeTop top(body, start);
  ASSERT_EQ(top.regime(), LagrangeTop::Regime::kNutating);
  EXPECT_EQ(top.u_max(), 1.0);
  const Agreement worst = agreement(body, start, 0.1, 5.0);
  EXPECT_LT(worst.orientation, 1e-10);
  EXPECT_LT(worst.momentum, 1e-10);
}

TEST(LagrangeTop, AgreesWithDopriNearTheVerticalAndThroughTheBottom) {
  // Tilted 1e-3 rad with a sideways swing: the axis passes within 1e-6 rad of the vertical,
  // where Delta turns by nearly 2 pi in a moment (the pole of the third-kind integral at
  // n+ -> 1, where 1 - n+ must come from 1 - u2, not from n+). And a pendulum released level at
  // rest: u swings through -1 (hanging straight down) and back up to 0.
  const BodyModel body = heavy_top();
  const Agreement near =
      agreement(body, tilted(body, 1e-6, Eigen::Vector3d(1.5, 0.0, 8.0)), 0.1, 5.0);
  EXPECT_LT(near.orientation, 1e-10);
  EXPECT_LT(near.momentum, 1e-10);
  // Released 1e-9 rad from hanging, spinning and swung sideways: it passes within about that of
  // straight down, where n- -> -inf and Pi(n-) ~ 1/sqrt(-n-) needs the dual form n' = m / n.
  const Agreement low = agreement(
      body, tilted(body, std::numbers::pi - 1e-9, Eigen::Vector3d(1.5, 0.0, 8.0)), 0.1, 3.0);
  EXPECT_LT(low.orientation, 1e-10);
  EXPECT_LT(low.momentum, 1e-10);
  // A slow top swung from 1e-9 rad off the upright: it falls through (almost) straight down and
  // comes back to (almost) the vertical, near both poles in each nutation.
  const Agreement over =
      agreement(body, tilted(body, 1e-9, Eigen::Vector3d(0.3, 0.2, 0.0)), 0.1, 3.0);
  EXPECT_LT(over.orientation, 1e-10);
  EXPECT_LT(over.momentum, 1e-10);
  const BodyState level = tilted(body, 0.5 * std::numbers::pi, Eigen::Vector3d::Zero());
  const LagrangeTop pendulum(body, level);
  EXPECT_NEAR(pendulum.u_min(), -1.0, 1e-15);
  EXPECT_NEAR(pendulum.u_max(), 0.0, 1e-15);
  const Agreement swing = agreement(body, level, 0.1, 5.0);
  EXPECT_LT(swing.orientation, 1e-10);
  EXPECT_LT(swing.momentum, 1e-10);
}

TEST(LagrangeTop, StartsAtTheInitialStateAndKeepsItsInvariantsToRounding) {
  const BodyModel body = heavy_top();
  const BodyState start = tilted(body, 0.7, Eigen::Vector3d(0.8, -1.3, 20.0));
  const LagrangeTop top(body, start);
  const BodyState zero = top.at(0.0);
  EXPECT_LT(orientation_angle(zero.orientation, start.orientation), 1e-15);
  EXPECT_LT((zero.angular_momentum - start.angular_momentum).norm(), 1e-14);

  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  const double energy0 = tumble::engine::energy(body, zero);
  const double l3 = start.angular_momentum.dot(start.orientation * Eigen::Vector3d::UnitZ());
  const double lz = start.angular_momentum.dot(up);
  const double scale = start.angular_momentum.norm();
  for (double t = 0.37; t < 1000.0; t *= 1.7) {
    const BodyState s = top.at(t);
    EXPECT_NEAR(tumble::engine::energy(body, s), energy0, 1e-13 * std::abs(energy0)) << t;
    EXPECT_NEAR(s.angular_momentum.dot(s.orientation * Eigen::Vector3d::UnitZ()), l3, 1e-14 * scale)
        << t;
    EXPECT_NEAR(s.angular_momentum.dot(up), lz, 1e-14 * scale) << t;
  }
}

TEST(LagrangeTop, AFastTopPrecessesAtMglOverI3W3) {
  // Released with no precession: the mean precession rate tends to m g l / (I3 w3) as the spin
  // grows, with a relative correction e cos(theta), e = I1 m g l / (I3 w3)^2 (~1e-4 here), the
  // first term of the slow steady precession (I3 w3 - sqrt((I3 w3)^2 - 4 I1 m g l cos(theta)))
  // / (2 I1 cos(theta)) (the nutation adds terms of order e^2).
  const BodyModel body = heavy_top();
  const double spin = 500.0;
  const BodyState start = tilted(body, 0.3, Eigen::Vector3d(0.0, 0.0, spin));
  const LagrangeTop top(body, start);
  const double mgl = body.mass * kG * 0.5;
  const double l3 = 0.5 * spin;
  const double expected = mgl / l3;
  const double small = 1.25 * mgl / (l3 * l3);
  // Over whole nutation periods the azimuth of the axis advances at the mean rate.
  const double period = top.nutation_period();
  EXPECT_NEAR(period, 2.0 * std::numbers::pi * 1.25 / l3, 10.0 * small * period);
  const auto azimuth = [&](double t) {
    const Eigen::Vector3d axis = top.at(t).orientation * Eigen::Vector3d::UnitZ();
    return std::atan2(axis.y(), axis.x());
  };
  const double periods = 20.0;
  const double rate = (azimuth(periods * period) - azimuth(0.0)) / (periods * period);
  EXPECT_NEAR(rate / expected - 1.0, small * std::cos(0.3), 0.05 * small);
}

TEST(LagrangeTop, TheSleepingTopSpinsInPlace) {
  const BodyModel body = heavy_top();
  const BodyState start = tumble::engine::spinning_state(body, Eigen::Quaterniond::Identity(),
                                                         Eigen::Vector3d(0, 0, 50));
  const LagrangeTop top(body, start);
  EXPECT_EQ(top.regime(), LagrangeTop::Regime::kSteady);
  for (const double t : {0.1, 3.0, 77.7}) {
    const BodyState s = top.at(t);
    const Eigen::Quaterniond turned(Eigen::AngleAxisd(50.0 * t, Eigen::Vector3d::UnitZ()));
    EXPECT_LT(orientation_angle(s.orientation, turned), 1e-13 * (1.0 + 50.0 * t)) << t;
    EXPECT_LT((s.angular_momentum - start.angular_momentum).norm(), 1e-13) << t;
  }
}

TEST(LagrangeTop, SteadyPrecessionKeepsItsTiltAndRate) {
  // The slow steady precession at tilt theta: phi' (I3 w3 - I1 phi' cos theta) = m g l, with
  // w3 = psi' + phi' cos theta, so phi' = (I3 w3 - sqrt((I3 w3)^2 - 4 I1 m g l cos theta))
  // / (2 I1 cos theta); the body's w is phi' up + psi' axis.
  const BodyModel body = heavy_top();
  const double theta = 0.4, w3 = 30.0, mgl = 0.5 * kG;
  const double l3 = 0.5 * w3, c = std::cos(theta);
  const double precession = (l3 - std::sqrt(l3 * l3 - 4.0 * 1.25 * mgl * c)) / (2.0 * 1.25 * c);
  const Eigen::Quaterniond q(Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitX()));
  const Eigen::Vector3d axis = q * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d omega_world =
      precession * Eigen::Vector3d::UnitZ() + (w3 - precession * c) * axis;
  const BodyState start = tumble::engine::spinning_state(body, q, q.conjugate() * omega_world);
  const LagrangeTop top(body, start);
  EXPECT_LT(top.u_max() - top.u_min(), 1e-12);
  for (const double t : {0.5, 4.0, 31.0}) {
    const BodyState s = top.at(t);
    const Eigen::Quaterniond expected =
        Eigen::Quaterniond(Eigen::AngleAxisd(precession * t, Eigen::Vector3d::UnitZ())) * q *
        Eigen::Quaterniond(Eigen::AngleAxisd((w3 - precession * c) * t, Eigen::Vector3d::UnitZ()));
    EXPECT_LT(orientation_angle(s.orientation, expected), 1e-12 * (1.0 + w3 * t)) << t;
  }
}

TEST(LagrangeTop, AHangingTopAtRestStaysAtRest) {
  const BodyModel body = heavy_top();
  const Eigen::Quaterniond down(0.0, 1.0, 0.0, 0.0);  // half a turn about x, exactly
  const BodyState start = tumble::engine::spinning_state(body, down, Eigen::Vector3d::Zero());
  const LagrangeTop top(body, start);
  EXPECT_EQ(top.regime(), LagrangeTop::Regime::kSteady);
  EXPECT_EQ(top.u_min(), -1.0);
  for (const double t : {0.5, 100.0}) {
    const BodyState s = top.at(t);
    EXPECT_LT(orientation_angle(s.orientation, start.orientation), 1e-15) << t;
    EXPECT_LT(s.angular_momentum.norm(), 1e-15) << t;
    EXPECT_NEAR(s.position.z(), -0.5, 1e-15) << t;
  }
}

TEST(LagrangeTop, ThePredicateRefusesWhatIsNotALagrangeTop) {
  EXPECT_TRUE(tumble::engine::is_lagrange_top(heavy_top()));
  BodyModel body = heavy_top();
  body.moments = Eigen::Vector3d(1.2, 1.25, 0.5);
  EXPECT_THAT(tumble::engine::lagrange_top_problem(body).value_or(""),
              ::testing::HasSubstr("not a symmetric top"));
  body = heavy_top();
  body.center_offset = Eigen::Vector3d(0.01, 0.0, 0.5);
  EXPECT_THAT(tumble::engine::lagrange_top_problem(body).value_or(""),
              ::testing::HasSubstr("not on a principal axis"));
  body = heavy_top();
  body.forces.emplace_back(tumble::engine::ConstantTorque{Eigen::Vector3d(0, 0, 1), false});
  EXPECT_FALSE(tumble::engine::is_lagrange_top(body));
  body = heavy_top();
  body.forces.emplace_back(
      tumble::engine::Spring{Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, 1), 1.0, 0.0});
  EXPECT_FALSE(tumble::engine::is_lagrange_top(body));
  body = heavy_top();
  body.pivoted = false;
  EXPECT_FALSE(tumble::engine::is_lagrange_top(body));
  EXPECT_THROW(LagrangeTop(body, BodyState{}), tumble::InputError);
}

TEST(LagrangeTop, TheExactIntegratorRunsAHeavyTopAndRefusesOtherForcedBodies) {
  const BodyModel body = heavy_top();
  const BodyState start = tilted(body, 0.3, Eigen::Vector3d(0.0, 0.0, 50.0));
  tumble::engine::SimulationSettings settings;
  settings.integrator = tumble::engine::IntegratorKind::kExact;
  settings.dt = 0.3;
  settings.duration = 3.0;
  tumble::engine::Simulation simulation({body}, {start}, settings);
  while (simulation.step()) {
  }
  EXPECT_FALSE(simulation.blow_up().has_value());
  const BodyState exact = LagrangeTop(body, start).at(3.0);
  EXPECT_LT(orientation_angle(simulation.states().front().orientation, exact.orientation), 1e-15);
  EXPECT_LT((simulation.states().front().position - exact.position).norm(), 1e-15);

  BodyModel sprung = body;
  sprung.forces.emplace_back(
      tumble::engine::Spring{Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, 1), 1.0, 0.0});
  try {
    tumble::engine::Simulation refused({sprung}, {start}, settings);
    ADD_FAILURE() << "a sprung top was accepted";
  } catch (const tumble::InputError& error) {
    EXPECT_THAT(error.what(),
                ::testing::HasSubstr("the exact integrator needs a torque-free body"));
    EXPECT_THAT(error.what(), ::testing::HasSubstr("torque or a spring"));
  }
}

TEST(LagrangeTop, TheReferenceOfAHeavyTopIsExact) {
  using tumble::engine::ReferenceMotion;
  const BodyModel body = heavy_top();
  BodyModel free_body;
  free_body.moments = Eigen::Vector3d(1.0, 2.0, 3.0);
  const std::vector<BodyState> start = {
      tilted(body, 0.3, Eigen::Vector3d(0.0, 0.0, 50.0)),
      tumble::engine::spinning_state(free_body, Eigen::Quaterniond::Identity(),
                                     Eigen::Vector3d(1.0, 0.5, 2.0))};
  const ReferenceMotion reference({body, free_body}, start);
  EXPECT_EQ(reference.kind(), ReferenceMotion::Kind::kExactWithTops);
  EXPECT_EQ(reference.integrator(), tumble::engine::IntegratorKind::kExact);
  EXPECT_EQ(reference.label(), "exact top");
  EXPECT_FALSE(reference.check_run().has_value());
  const std::vector<BodyState> at = reference.at(2.0);
  EXPECT_LT(orientation_angle(at[0].orientation, LagrangeTop(body, start[0]).at(2.0).orientation),
            1e-15);
  const tumble::engine::TorqueFreeMotion free_motion(free_body.moments, start[1].orientation,
                                                     Eigen::Vector3d(1.0, 0.5, 2.0));
  EXPECT_LT(orientation_angle(at[1].orientation, free_motion.at(2.0).orientation), 1e-15);

  BodyModel sprung = body;
  sprung.forces.emplace_back(
      tumble::engine::Spring{Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, 1), 1.0, 0.0});
  EXPECT_EQ(ReferenceMotion({sprung}, {start[0]}).kind(), ReferenceMotion::Kind::kDopri);
}

}  // namespace
