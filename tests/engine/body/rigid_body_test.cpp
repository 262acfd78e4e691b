// One body's invariants and rotation centre against closed forms worked out by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "engine/body/rigid_body.hpp"

namespace {

using tumble::engine::BodyModel;
using tumble::engine::BodyState;
using tumble::engine::ConstantTorque;
using tumble::engine::Gravity;
using tumble::engine::InvariantSum;
using tumble::engine::Spring;

/// A uniform 1 x 2 x 3 m box of 6 kg: I_x = m (b^2 + c^2) / 12 = 6.5, I_y = 5, I_z = 2.5.
BodyModel box() {
  BodyModel body;
  body.mass = 6.0;
  body.moments = Eigen::Vector3d(6.5, 5.0, 2.5);
  return body;
}

/// A quarter turn about world z: principal x goes to world y.
const Eigen::Quaterniond kQuarterTurnZ(Eigen::AngleAxisd(std::numbers::pi / 2,
                                                         Eigen::Vector3d::UnitZ()));

TEST(Invariants, SpinningBoxHasHalfOmegaIOmegaAndTheNormOfIOmega) {
  const BodyModel body = box();
  const Eigen::Quaterniond turn(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  BodyState state = tumble::engine::spinning_state(body, turn, Eigen::Vector3d(1.0, -2.0, 0.5));
  state.velocity = Eigen::Vector3d(0.0, 3.0, 4.0);  // |v| = 5
  // E = (6.5 * 1 + 5 * 4 + 2.5 * 0.25) / 2 + 6 * 25 / 2 = 13.5625 + 75;
  // |L| = |(6.5, -10, 1.25)| = sqrt(42.25 + 100 + 1.5625).
  const auto got = tumble::engine::invariants(body, state);
  EXPECT_NEAR(got.energy, 88.5625, 1e-13);
  EXPECT_NEAR(got.momentum, std::sqrt(143.8125), 1e-13);
}

TEST(Invariants, GravityAndASpringAddTheirPotentials) {
  BodyModel body = box();
  body.forces.emplace_back(Gravity{Eigen::Vector3d(0.0, 0.0, -9.81)});
  body.forces.emplace_back(
      Spring{Eigen::Vector3d(0.0, 1.0, 0.0), Eigen::Vector3d(1.0, 0.0, 0.0), 3.0, 0.0});
  BodyState state;  // at rest, no kinetic energy
  state.position = Eigen::Vector3d(0.0, 0.0, 2.0);
  state.orientation = kQuarterTurnZ;  // the attach point (1, 0, 0) is at world (0, 1, 2)
  // -m g . x = 6 * 9.81 * 2; the spring is stretched by 2 m: k 2^2 / 2 = 6.
  const auto got = tumble::engine::invariants(body, state);
  EXPECT_NEAR(got.energy, 117.72 + 6.0, 1e-12);
  EXPECT_EQ(got.momentum, 0.0);
}

TEST(Invariants, SumsTakeEveryBodyOrOnlyWhereConserved) {
  BodyModel free = box();
  BodyModel torqued = box();
  torqued.forces.emplace_back(ConstantTorque{Eigen::Vector3d(0.0, 0.0, 1.0), false});
  BodyModel damped = box();
  damped.forces.emplace_back(
      Spring{Eigen::Vector3d::Zero(), Eigen::Vector3d(1.0, 0.0, 0.0), 2.0, 0.5});
  const std::vector<BodyModel> bodies = {free, torqued, damped};
  // Each spins at 2 rad/s about principal z (E = 2.5 * 4 / 2 = 5, |L| = 5); the damped spring's
  // attach point sits 1 m from its anchor (k 1^2 / 2 = 1).
  const BodyState spin = tumble::engine::spinning_state(free, Eigen::Quaterniond::Identity(),
                                                        Eigen::Vector3d(0, 0, 2));
  const std::vector<BodyState> states = {spin, spin, spin};

  const auto all = tumble::engine::total_invariants(bodies, states);
  EXPECT_NEAR(all.energy, 5.0 + 5.0 + 6.0, 1e-14);
  EXPECT_NEAR(all.momentum, 15.0, 1e-14);
  // Energy: the torque and the damper are not conservative; |L|: only the free body is
  // torque-free (the spring pulls off the centre of mass).
  const auto conserved =
      tumble::engine::total_invariants(bodies, states, InvariantSum::kWhereConserved);
  EXPECT_NEAR(conserved.energy, 5.0, 1e-14);
  EXPECT_NEAR(conserved.momentum, 5.0, 1e-14);
}

TEST(RotationCentre, IsTheCentreOfMassOfAFreeBodyAndThePivotOfATop) {
  const BodyModel free = box();
  BodyState state;
  state.position = Eigen::Vector3d(1.0, -2.0, 3.0);
  state.orientation = kQuarterTurnZ;
  EXPECT_EQ(tumble::engine::rotation_centre(free, state), state.position);

  BodyModel top = box();
  top.pivoted = true;
  top.pivot = Eigen::Vector3d(0.5, 0.5, 0.0);
  top.center_offset = Eigen::Vector3d(1.0, 0.0, 0.0);
  tumble::engine::update_pivot_kinematics(top, state);
  // The centre of mass is one metre from the pivot along principal x, now world y.
  EXPECT_NEAR((state.position - Eigen::Vector3d(0.5, 1.5, 0.0)).norm(), 0.0, 1e-15);
  EXPECT_EQ(tumble::engine::rotation_centre(top, state), top.pivot);
}

}  // namespace
