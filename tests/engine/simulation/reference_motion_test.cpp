// The one reference motion: the exact solution for torque-free bodies, dopri at
// kReferenceTolerance otherwise, each checked against closed forms worked out here.
#include "engine/simulation/reference_motion.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "engine/dynamics/integrators.hpp"
#include "engine/exact/torque_free_exact.hpp"

namespace {

using tumble::engine::BodyModel;
using tumble::engine::BodyState;
using tumble::engine::ReferenceMotion;

/// An asymmetric body tumbling about its largest axis, and a sphere thrown
/// under gravity: both torque-free.
struct FreeScene {
  std::vector<BodyModel> bodies;
  std::vector<BodyState> initial;
};

FreeScene free_scene() {
  FreeScene scene;
  BodyModel handle;
  handle.moments = Eigen::Vector3d(1.0, 2.0, 3.0);
  const Eigen::Quaterniond turn(Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, -1, 2).normalized()));
  scene.bodies.push_back(handle);
  scene.initial.push_back(
      tumble::engine::spinning_state(handle, turn, Eigen::Vector3d(1.0, 0.5, 2.0)));

  BodyModel ball;
  ball.mass = 2.0;
  ball.moments = Eigen::Vector3d(0.5, 0.5, 0.5);
  ball.forces.emplace_back(tumble::engine::Gravity{Eigen::Vector3d(0.0, 0.0, -10.0)});
  BodyState thrown = tumble::engine::spinning_state(ball, Eigen::Quaterniond::Identity(),
                                                    Eigen::Vector3d(1, 0, 0));
  thrown.position = Eigen::Vector3d(1.0, 2.0, 3.0);
  thrown.velocity = Eigen::Vector3d(0.5, 0.0, 4.0);
  scene.bodies.push_back(ball);
  scene.initial.push_back(thrown);
  return scene;
}

TEST(ReferenceMotion, TorqueFreeBodiesGetTheExactSolution) {
  const FreeScene scene = free_scene();
  const ReferenceMotion reference(scene.bodies, scene.initial);
  EXPECT_EQ(reference.kind(), ReferenceMotion::Kind::kExact);
  EXPECT_EQ(reference.integrator(), tumble::engine::IntegratorKind::kExact);
  EXPECT_EQ(reference.description(), "exact torque-free solution (Jacobi elliptic functions)");
  EXPECT_EQ(reference.label(), "exact");
  EXPECT_FALSE(reference.check_run().has_value());

  // The handle turns as TorqueFreeMotion says, from w = (1, 0.5, 2) in principal axes.
  const tumble::engine::TorqueFreeMotion exact(
      scene.bodies[0].moments, scene.initial[0].orientation, Eigen::Vector3d(1.0, 0.5, 2.0));
  const double t = 7.3;
  const std::vector<BodyState> states = reference.at(t);
  ASSERT_EQ(states.size(), 2u);
  EXPECT_LT(tumble::engine::orientation_angle(states[0].orientation, exact.at(t).orientation),
            1e-13);
  EXPECT_EQ(states[0].angular_momentum, scene.initial[0].angular_momentum);  // L is constant
  // The ball's centre on its parabola, x0 + v0 t + g t^2 / 2; v = v0 + g t.
  const Eigen::Vector3d position(1.0 + 0.5 * t, 2.0, 3.0 + 4.0 * t - 5.0 * t * t);
  EXPECT_LT((states[1].position - position).norm(), 1e-12);
  EXPECT_LT((states[1].velocity - Eigen::Vector3d(0.5, 0.0, 4.0 - 10.0 * t)).norm(), 1e-13);
  // A sphere spinning about x stays on that axis: a turn by w t = t rad.
  const Eigen::Quaterniond spun(Eigen::AngleAxisd(t, Eigen::Vector3d::UnitX()));
  EXPECT_LT(tumble::engine::orientation_angle(states[1].orientation, spun), 1e-13);
}

TEST(ReferenceMotion, SamplesSitAtTheSimulationInstants) {
  const FreeScene scene = free_scene();
  const ReferenceMotion reference(scene.bodies, scene.initial);
  // Output step 0.3 to 1: t = 0.3, 0.6, 0.9 and the last at 1 exactly.
  const auto samples = reference.sample(0.3, 1.0);
  ASSERT_EQ(samples.size(), 4u);
  const double times[] = {0.3, 0.6, 0.9, 1.0};
  for (std::size_t k = 0; k < 4; ++k) {
    const double t = times[k];
    EXPECT_NEAR(samples[k][1].position.z(), 3.0 + 4.0 * t - 5.0 * t * t, 1e-14) << k;
  }
}

/// A sphere (I = 0.5) under a constant world torque (0, 0, 2) along its spin L0 = (0, 0, 1),
/// and a ball on a spring at its centre of mass (m = 2, k = 8: w = 2 rad/s).
struct ForcedScene {
  std::vector<BodyModel> bodies;
  std::vector<BodyState> initial;
};

ForcedScene forced_scene() {
  ForcedScene scene;
  BodyModel sphere;
  sphere.moments = Eigen::Vector3d(0.5, 0.5, 0.5);
  sphere.forces.emplace_back(tumble::engine::ConstantTorque{Eigen::Vector3d(0.0, 0.0, 2.0), false});
  scene.bodies.push_back(sphere);
  scene.initial.push_back(tumble::engine::spinning_state(sphere, Eigen::Quaterniond::Identity(),
                                                         Eigen::Vector3d(0, 0, 2)));

  BodyModel ball;
  ball.mass = 2.0;
  ball.forces.emplace_back(
      tumble::engine::Spring{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), 8.0, 0.0});
  BodyState released;
  released.position = Eigen::Vector3d(0.3, 0.0, 0.0);
  scene.bodies.push_back(ball);
  scene.initial.push_back(released);
  return scene;
}

TEST(ReferenceMotion, ForcedBodiesGetDopriAtTheReferenceTolerance) {
  const ForcedScene scene = forced_scene();
  const ReferenceMotion reference(scene.bodies, scene.initial);
  EXPECT_EQ(reference.kind(), ReferenceMotion::Kind::kDopri);
  EXPECT_EQ(reference.integrator(), tumble::engine::IntegratorKind::kDopri);
  EXPECT_EQ(reference.tolerance(), tumble::engine::kReferenceTolerance);
  EXPECT_EQ(reference.description(), "dopri at tolerance 1e-13");
  EXPECT_EQ(reference.label(), "dopri 1e-13");

  // Closed forms: the sphere turns about z by 2 t + 2 t^2 (L = L0 + tau t, w = L / I); the
  // ball oscillates, x = 0.3 cos(2 t).
  const double t = 1.5;
  const std::vector<BodyState> states = reference.at(t);
  const Eigen::Quaterniond turned(
      Eigen::AngleAxisd(2.0 * t + 2.0 * t * t, Eigen::Vector3d::UnitZ()));
  EXPECT_LT(tumble::engine::orientation_angle(states[0].orientation, turned), 1e-11);
  EXPECT_NEAR(states[0].angular_momentum.z(), 1.0 + 2.0 * t, 1e-12);
  EXPECT_NEAR(states[1].position.x(), 0.3 * std::cos(2.0 * t), 1e-12);
  EXPECT_NEAR(states[1].velocity.x(), -0.6 * std::sin(2.0 * t), 1e-12);
}

TEST(ReferenceMotion, TheCheckRunIsADecadeLooserAndAgreesOnThatScale) {
  const ForcedScene scene = forced_scene();
  const ReferenceMotion reference(scene.bodies, scene.initial);
  const auto check = reference.check_run();
  ASSERT_TRUE(check.has_value());
  EXPECT_EQ(check->tolerance(), tumble::engine::kReferenceCheckTolerance);
  EXPECT_EQ(check->label(), "dopri 1e-12");

  const auto tight = reference.sample(0.25, 3.0);
  const auto loose = check->sample(0.25, 3.0);
  ASSERT_EQ(tight.size(), 12u);
  ASSERT_EQ(loose.size(), 12u);
  double worst_tight = 0.0;
  double worst_loose = 0.0;
  double difference = 0.0;
  for (std::size_t k = 0; k < tight.size(); ++k) {
    const double t = 0.25 * static_cast<double>(k + 1);
    const double x = 0.3 * std::cos(2.0 * t);
    worst_tight = std::max(worst_tight, std::abs(tight[k][1].position.x() - x));
    worst_loose = std::max(worst_loose, std::abs(loose[k][1].position.x() - x));
    difference =
        std::max(difference, std::abs(tight[k][1].position.x() - loose[k][1].position.x()));
  }
  // Both within a few tens of tolerances of the oscillator's amplitude over 3 s; the tighter
  // run is the closer; they differ by about the looser run's error.
  EXPECT_LT(worst_tight, 30.0 * tumble::engine::kReferenceTolerance);
  EXPECT_LT(worst_loose, 30.0 * tumble::engine::kReferenceCheckTolerance);
  EXPECT_LT(worst_tight, worst_loose);
  EXPECT_LT(difference, 2.0 * worst_loose);
  EXPECT_GT(difference, 0.5 * worst_loose);
}

}  // namespace
