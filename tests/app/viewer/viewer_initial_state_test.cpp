#include "app/viewer/viewer_initial_state.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <stdexcept>
#include <string>

#include <Eigen/Geometry>

#include "app/scene/scene.hpp"
#include "engine/body/rigid_body.hpp"

namespace tumble::app::viewer {
namespace {

using ::testing::HasSubstr;

constexpr double kInitialDeg = std::numbers::pi / 180.0;

// --- Independent oracles: rotation matrices written out from cos and sin ------------------------

Eigen::Matrix3d rot_x(double deg) {
  const double c = std::cos(deg * kInitialDeg), s = std::sin(deg * kInitialDeg);
  Eigen::Matrix3d m;
  m << 1, 0, 0, 0, c, -s, 0, s, c;
  return m;
}
Eigen::Matrix3d rot_y(double deg) {
  const double c = std::cos(deg * kInitialDeg), s = std::sin(deg * kInitialDeg);
  Eigen::Matrix3d m;
  m << c, 0, s, 0, 1, 0, -s, 0, c;
  return m;
}
Eigen::Matrix3d rot_z(double deg) {
  const double c = std::cos(deg * kInitialDeg), s = std::sin(deg * kInitialDeg);
  Eigen::Matrix3d m;
  m << c, -s, 0, s, c, 0, 0, 0, 1;
  return m;
}
/// Body-to-world rotation of intrinsic z-y'-x'' angles.
Eigen::Matrix3d ypr_matrix(const Eigen::Vector3d& ypr_deg) {
  return rot_z(ypr_deg[0]) * rot_y(ypr_deg[1]) * rot_x(ypr_deg[2]);
}

/// Angle (rad) of the rotation a^T b, from its trace (adequate above ~1e-7 rad) and its
/// antisymmetric part (accurate for tiny angles).
double rotation_angle(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  const Eigen::Matrix3d d = a.transpose() * b;
  const Eigen::Vector3d axis(d(2, 1) - d(1, 2), d(0, 2) - d(2, 0), d(1, 0) - d(0, 1));
  return std::atan2(0.5 * axis.norm(), 0.5 * (d.trace() - 1.0));
}

void expect_vec_near(const Eigen::Vector3d& actual, const Eigen::Vector3d& expected, double tol) {
  EXPECT_NEAR(actual.x(), expected.x(), tol)
      << "actual " << actual.transpose() << ", expected " << expected.transpose();
  EXPECT_NEAR(actual.y(), expected.y(), tol)
      << "actual " << actual.transpose() << ", expected " << expected.transpose();
  EXPECT_NEAR(actual.z(), expected.z(), tol)
      << "actual " << actual.transpose() << ", expected " << expected.transpose();
}

/// A free body with three distinct moments whose principal axes are turned away from its body
/// axes (so body and principal frames differ), in a general orientation.
struct FreeBody {
  engine::BodyModel model;
  engine::BodyState state;
  Eigen::Matrix3d P;  ///< principal -> body
  Eigen::Matrix3d R;  ///< principal -> world
  Eigen::Matrix3d J;  ///< diag(moments)
};

FreeBody free_body() {
  FreeBody b;
  b.model.name = "brick";
  b.model.mass = 2.5;
  b.model.moments = Eigen::Vector3d(0.7, 1.9, 2.3);
  b.P = rot_z(35.0) * rot_x(-50.0);
  b.model.principal_to_body = Eigen::Quaterniond(b.P);
  b.R = rot_x(20.0) * rot_y(-65.0) * rot_z(110.0);
  b.state.orientation = Eigen::Quaterniond(b.R);
  b.state.position = Eigen::Vector3d(1.0, -2.0, 0.5);
  b.J = b.model.moments.asDiagonal();
  return b;
}

/// A top: pivoted, gravity along -z, centre of mass off the pivot along a general principal
/// direction.
engine::BodyModel top_model(const Eigen::Vector3d& gravity = Eigen::Vector3d(0, 0, -9.81)) {
  engine::BodyModel top;
  top.name = "top";
  top.mass = 0.3;
  top.moments = Eigen::Vector3d(2e-4, 2e-4, 1e-4);
  top.principal_to_body = Eigen::Quaterniond(rot_y(15.0) * rot_z(40.0));
  top.pivoted = true;
  top.pivot = Eigen::Vector3d(0.2, -0.1, 0.05);
  top.center_offset = Eigen::Vector3d(0.004, -0.003, 0.03);
  top.forces.push_back(engine::Gravity{gravity});
  return top;
}

// --- Angular velocity --------------------------------------------------------------------------

TEST(ViewerInitialState, WorldOmegaRoundTripAndMomentumIsRJRtW) {
  FreeBody b = free_body();
  const Eigen::Vector3d w(0.3, -1.2, 2.5);
  set_initial_omega(b.model, b.state, w, VectorFrame::kWorld);

  expect_vec_near(initial_omega(b.model, b.state, VectorFrame::kWorld), w, 1e-13);
  // World L = R J R^T w about the centre of mass.
  expect_vec_near(b.state.angular_momentum, b.R * b.J * b.R.transpose() * w, 1e-13);
  // In the body frame, w_body = B^T w with B = R P^T (body -> world).
  const Eigen::Matrix3d B = b.R * b.P.transpose();
  expect_vec_near(initial_omega(b.model, b.state, VectorFrame::kBody), B.transpose() * w, 1e-13);
  // A free body's centre of mass is not touched.
  EXPECT_EQ(b.state.position, Eigen::Vector3d(1.0, -2.0, 0.5));
  EXPECT_EQ(b.state.velocity, Eigen::Vector3d::Zero());
}

TEST(ViewerInitialState, BodyOmegaRoundTripUsesTheBodyInertiaTensor) {
  FreeBody b = free_body();
  const Eigen::Vector3d w_body(-0.8, 0.4, 3.0);
  set_initial_omega(b.model, b.state, w_body, VectorFrame::kBody);

  expect_vec_near(initial_omega(b.model, b.state, VectorFrame::kBody), w_body, 1e-13);
  const Eigen::Matrix3d B = b.R * b.P.transpose();
  expect_vec_near(initial_omega(b.model, b.state, VectorFrame::kWorld), B * w_body, 1e-13);
  // L in body axes is the body-frame inertia tensor P J P^T times w_body.
  const Eigen::Matrix3d inertia_body = b.P * b.J * b.P.transpose();
  expect_vec_near(B.transpose() * b.state.angular_momentum, inertia_body * w_body, 1e-13);
}

TEST(ViewerInitialState, EnergyIsHalfWDotL) {
  FreeBody b = free_body();
  const Eigen::Vector3d w(1.5, 0.25, -0.75);
  set_initial_omega(b.model, b.state, w, VectorFrame::kWorld);
  const double expected = 0.5 * w.dot(b.R * b.J * b.R.transpose() * w);
  EXPECT_NEAR(engine::energy(b.model, b.state), expected, 1e-13 * expected);
  // Closed form in the principal frame: 0.5 sum I_k w_k^2.
  const Eigen::Vector3d local = b.R.transpose() * w;
  EXPECT_NEAR(
      expected,
      0.5 * (0.7 * local[0] * local[0] + 1.9 * local[1] * local[1] + 2.3 * local[2] * local[2]),
      1e-13 * expected);
}

TEST(ViewerInitialState, PivotedBodyCentreOfMassVelocityFollowsOmega) {
  engine::BodyModel top = top_model();
  engine::BodyState state;
  state.orientation = Eigen::Quaterniond(rot_x(10.0) * rot_z(-30.0));
  const Eigen::Vector3d w(0.5, 2.0, 30.0);
  set_initial_omega(top, state, w, VectorFrame::kWorld);
  const Eigen::Matrix3d R = state.orientation.toRotationMatrix();
  const Eigen::Vector3d arm = R * top.center_offset;
  expect_vec_near(state.position, top.pivot + arm, 1e-14);
  expect_vec_near(state.velocity, w.cross(arm), 1e-13);
  // L is about the pivot (moments given about the pivot).
  expect_vec_near(state.angular_momentum, R * top.moments.asDiagonal() * R.transpose() * w, 1e-14);
}

// --- Yaw, pitch, roll --------------------------------------------------------------------------

TEST(ViewerInitialState, YawPitchRollRoundTrip) {
  FreeBody b = free_body();
  const Eigen::Vector3d cases[] = {{0, 0, 0},        {30, 20, 10},     {-170, 80, 175},
                                   {120, -45, -60},  {179, -89, 1},    {-90, 0.5, 90},
                                   {45, 89.99, -30}, {-10, -89.99, 60}};
  for (const Eigen::Vector3d& ypr : cases) {
    set_orientation_ypr_deg(b.model, b.state, ypr);
    const Eigen::Vector3d back = orientation_ypr_deg(b.model, b.state);
    expect_vec_near(back, ypr, 1e-8);
    // The body frame (not the principal frame) is the one turned to yaw, pitch, roll.
    const Eigen::Matrix3d body_to_world = b.state.orientation.toRotationMatrix() * b.P.transpose();
    EXPECT_LT(rotation_angle(body_to_world, ypr_matrix(ypr)), 1e-12) << ypr.transpose();
  }
}

TEST(ViewerInitialState, AnglesAreReadFromAnyOrientation) {
  // Orientation set directly (not through the setter): R_body = Rz(-40) Ry(25) Rx(130).
  FreeBody b = free_body();
  const Eigen::Vector3d ypr(-40, 25, 130);
  b.state.orientation = Eigen::Quaterniond(ypr_matrix(ypr) * b.P);
  expect_vec_near(orientation_ypr_deg(b.model, b.state), ypr, 1e-10);
  // An angle outside [-90, 90] of pitch comes back as the equivalent triple in range:
  // (y, 180 - p, r) names the same rotation as (y + 180, p, r + 180).
  b.state.orientation = Eigen::Quaterniond(ypr_matrix({10, 120, 20}) * b.P);
  const Eigen::Vector3d back = orientation_ypr_deg(b.model, b.state);
  expect_vec_near(back, Eigen::Vector3d(-170, 60, -160), 1e-10);
}

TEST(ViewerInitialState, GimbalLockGivesTheSameRotation) {
  FreeBody b = free_body();
  // At pitch +90 only yaw - roll is defined, at -90 only yaw + roll: all of it goes to yaw.
  struct Case {
    Eigen::Vector3d set;
    Eigen::Vector3d expected;
  };
  const Case exact[] = {
      {{30, 90, 10}, {20, 90, 0}}, {{30, -90, 10}, {40, -90, 0}}, {{-150, 90, 60}, {150, 90, 0}}};
  for (const Case& c : exact) {
    set_orientation_ypr_deg(b.model, b.state, c.set);
    const Eigen::Vector3d back = orientation_ypr_deg(b.model, b.state);
    expect_vec_near(back, c.expected, 1e-5);
    EXPECT_LT(rotation_angle(ypr_matrix(back), ypr_matrix(c.set)), 1e-7) << c.set.transpose();
  }
  // Close to the lock (either branch of the code), the angles read back name the same rotation.
  for (const double pitch :
       {90.0 - 1e-9, 90.0 - 1e-7, 90.0 - 1e-5, 90.0 - 1e-3, -90.0 + 1e-7, -90.0 + 1e-4}) {
    const Eigen::Vector3d set(25.0, pitch, -35.0);
    set_orientation_ypr_deg(b.model, b.state, set);
    const Eigen::Vector3d back = orientation_ypr_deg(b.model, b.state);
    EXPECT_GE(back[1], -90.0);
    EXPECT_LE(back[1], 90.0);
    EXPECT_LT(rotation_angle(ypr_matrix(back), ypr_matrix(set)), 2e-6) << pitch;
    // And setting what was read back reproduces the orientation.
    const Eigen::Quaterniond before = b.state.orientation;
    set_orientation_ypr_deg(b.model, b.state, back);
    EXPECT_LT(engine::orientation_angle(before, b.state.orientation), 2e-6) << pitch;
  }
}

TEST(ViewerInitialState, TurningKeepsTheBodyFrameOmega) {
  FreeBody b = free_body();
  const Eigen::Vector3d w_body(0.2, -3.0, 1.1);
  set_initial_omega(b.model, b.state, w_body, VectorFrame::kBody);
  const Eigen::Vector3d ypr(75, -30, 15);
  set_orientation_ypr_deg(b.model, b.state, ypr);

  expect_vec_near(initial_omega(b.model, b.state, VectorFrame::kBody), w_body, 1e-13);
  // In the world, w turned with the body.
  expect_vec_near(initial_omega(b.model, b.state, VectorFrame::kWorld), ypr_matrix(ypr) * w_body,
                  1e-13);
  // |L| and the energy are the same: the same spin about the same body axis.
  const Eigen::Matrix3d inertia_body = b.P * b.J * b.P.transpose();
  EXPECT_NEAR(b.state.angular_momentum.norm(), (inertia_body * w_body).norm(), 1e-13);
  EXPECT_NEAR(engine::energy(b.model, b.state), 0.5 * w_body.dot(inertia_body * w_body), 1e-13);
  // A free body turns about its centre of mass.
  EXPECT_EQ(b.state.position, Eigen::Vector3d(1.0, -2.0, 0.5));
}

TEST(ViewerInitialState, TurningAPivotedBodyTurnsItAboutThePivot) {
  engine::BodyModel top = top_model();
  engine::BodyState state;
  const Eigen::Vector3d w_body(0.0, 1.0, 40.0);
  set_initial_omega(top, state, w_body, VectorFrame::kBody);
  const Eigen::Vector3d ypr(20, 35, -5);
  set_orientation_ypr_deg(top, state, ypr);
  const Eigen::Matrix3d P = top.principal_to_body.toRotationMatrix();
  // x = pivot + R_body (P c): the body-frame arm turned by the new orientation.
  const Eigen::Vector3d arm = ypr_matrix(ypr) * (P * top.center_offset);
  expect_vec_near(state.position, top.pivot + arm, 1e-14);
  const Eigen::Vector3d w = ypr_matrix(ypr) * w_body;
  expect_vec_near(state.velocity, w.cross(arm), 1e-12);
}

// --- Presets -----------------------------------------------------------------------------------

TEST(ViewerInitialState, PresetSpinsAboutEachPrincipalAxisWithAPerturbation) {
  for (int axis = 0; axis < 3; ++axis) {
    FreeBody b = free_body();
    const double rate = 6.0;
    const double p = 0.01;
    preset_principal_spin(b.model, b.state, axis, rate, p);
    // w in the principal frame, from L: w = J^-1 R^T L.
    const Eigen::Vector3d w_principal =
        b.J.inverse() * (b.R.transpose() * b.state.angular_momentum);
    Eigen::Vector3d expected = Eigen::Vector3d::Constant(rate * p);
    expected[axis] = rate;
    expect_vec_near(w_principal, expected, 1e-13);
    // Orientation untouched.
    EXPECT_LT(rotation_angle(b.state.orientation.toRotationMatrix(), b.R), 1e-14);
  }
}

TEST(ViewerInitialState, PresetRejectsABadAxis) {
  FreeBody b = free_body();
  const engine::BodyState before = b.state;
  for (const int axis : {-1, 3}) {
    try {
      preset_principal_spin(b.model, b.state, axis, 1.0, 0.0);
      ADD_FAILURE() << "no exception for axis " << axis;
    } catch (const std::out_of_range& error) {
      EXPECT_THAT(error.what(), HasSubstr("principal axis must be 0, 1 or 2"));
    }
  }
  EXPECT_EQ(b.state.angular_momentum, before.angular_momentum);
}

// --- Tops --------------------------------------------------------------------------------------

TEST(ViewerInitialState, WhatIsATop) {
  EXPECT_TRUE(is_top(top_model()));
  engine::BodyModel free = top_model();
  free.pivoted = false;
  EXPECT_FALSE(is_top(free));
  engine::BodyModel weightless = top_model();
  weightless.forces.clear();
  EXPECT_FALSE(is_top(weightless));
  EXPECT_FALSE(is_top(top_model(Eigen::Vector3d::Zero())));
  engine::BodyModel centred = top_model();
  centred.center_offset = Eigen::Vector3d::Zero();
  EXPECT_FALSE(is_top(centred));
  // Other force terms beside gravity do not matter.
  engine::BodyModel pushed = top_model();
  pushed.forces.insert(pushed.forces.begin(),
                       engine::ConstantTorque{Eigen::Vector3d(0, 0, 1e-3), true});
  EXPECT_TRUE(is_top(pushed));
}

TEST(ViewerInitialState, TopPoseRoundTripLeansTowardsPlusX) {
  const engine::BodyModel top = top_model();
  engine::BodyState state;
  state.orientation = Eigen::Quaterniond(rot_x(-25.0) * rot_z(70.0));
  const TopPose pose{20.0, 150.0};
  set_top_pose(top, state, pose);

  const TopPose back = top_pose(top, state);
  EXPECT_NEAR(back.tilt_deg, 20.0, 1e-10);
  EXPECT_NEAR(back.spin, 150.0, 1e-10);

  // The axis (pivot to centre of mass) is tilted 20 degrees from +z towards +x.
  const Eigen::Matrix3d R = state.orientation.toRotationMatrix();
  const Eigen::Vector3d axis = (R * top.center_offset).normalized();
  expect_vec_near(
      axis, Eigen::Vector3d(std::sin(20 * kInitialDeg), 0.0, std::cos(20 * kInitialDeg)), 1e-13);
  // w is along the axis with nothing else.
  expect_vec_near(engine::angular_velocity(top, state), 150.0 * axis, 1e-10);
  // Pivot kinematics: the centre of mass sits on the arm and does not move (w parallel to it).
  expect_vec_near(state.position, top.pivot + R * top.center_offset, 1e-14);
  expect_vec_near(state.velocity, Eigen::Vector3d::Zero(), 1e-12);
}

TEST(ViewerInitialState, TopPoseKeepsTheRollAboutItsAxis) {
  const engine::BodyModel top = top_model();
  engine::BodyState state;
  state.orientation = Eigen::Quaterniond(rot_y(12.0) * rot_z(-100.0));
  set_top_pose(top, state, {30.0, 80.0});
  const Eigen::Quaterniond at_30 = state.orientation;
  // The same pose again changes nothing (no turn about the top's own axis).
  set_top_pose(top, state, {30.0, 80.0});
  EXPECT_LT(engine::orientation_angle(state.orientation, at_30), 1e-12);
  // Upright and back: the same orientation as before.
  set_top_pose(top, state, {0.0, 80.0});
  EXPECT_NEAR(top_pose(top, state).tilt_deg, 0.0, 1e-5);
  set_top_pose(top, state, {30.0, -5.0});
  EXPECT_LT(engine::orientation_angle(state.orientation, at_30), 1e-12);
  EXPECT_NEAR(top_pose(top, state).spin, -5.0, 1e-12);
}

TEST(ViewerInitialState, TopUnderSidewaysGravityTiltsFromItsUp) {
  // Gravity along -x: up is +x; up x (+x) vanishes, so the top tilts about up x (+y) = +z,
  // from +x towards +y.
  const engine::BodyModel top = top_model(Eigen::Vector3d(-3.0, 0, 0));
  engine::BodyState state;
  set_top_pose(top, state, {40.0, 10.0});
  const TopPose back = top_pose(top, state);
  EXPECT_NEAR(back.tilt_deg, 40.0, 1e-10);
  EXPECT_NEAR(back.spin, 10.0, 1e-12);
  const Eigen::Vector3d axis = (state.orientation * top.center_offset).normalized();
  expect_vec_near(
      axis, Eigen::Vector3d(std::cos(40 * kInitialDeg), std::sin(40 * kInitialDeg), 0.0), 1e-13);
}

TEST(ViewerInitialState, HeavyTopSceneReadsItsTiltAndSpin) {
  const std::filesystem::path file =
      std::filesystem::path(TUMBLE_SOURCE_DIR) / "assets/scenes/heavy_top.json";
  const CompiledScene compiled = compile_scene(load_scene(file));
  ASSERT_EQ(compiled.bodies.size(), 1u);
  const engine::BodyModel& top = compiled.bodies[0];
  const engine::BodyState& state = compiled.initial[0];
  ASSERT_TRUE(is_top(top));
  // The scene's orientation [w, x, y, z] = [0.98877, 0.14944, 0, 0] turns the top's axis
  // (body +z, tip to centre of mass) about x by 2 atan2(x, w), and w = 120 rad/s about it.
  const double tilt = 2.0 * std::atan2(0.1494381325, 0.9887710779) / kInitialDeg;
  const TopPose pose = top_pose(top, state);
  EXPECT_NEAR(pose.tilt_deg, tilt, 1e-6);
  EXPECT_NEAR(pose.spin, 120.0, 1e-6);
  // The scene leans the top towards -y (a turn about +x); set_top_pose with the same pose leans
  // it towards +x instead, at the same tilt and spin, still spinning about its own body axis.
  const Eigen::Vector3d scene_axis = (state.orientation * top.center_offset).normalized();
  expect_vec_near(scene_axis,
                  Eigen::Vector3d(0, -std::sin(tilt * kInitialDeg), std::cos(tilt * kInitialDeg)),
                  1e-9);
  engine::BodyState copy = state;
  set_top_pose(top, copy, pose);
  const TopPose back = top_pose(top, copy);
  EXPECT_NEAR(back.tilt_deg, pose.tilt_deg, 1e-9);
  EXPECT_NEAR(back.spin, pose.spin, 1e-9);
  const Eigen::Vector3d arm = copy.orientation * top.center_offset;
  expect_vec_near(arm.normalized(),
                  Eigen::Vector3d(std::sin(tilt * kInitialDeg), 0, std::cos(tilt * kInitialDeg)),
                  1e-9);
  expect_vec_near(copy.position, top.pivot + arm, 1e-14);
  expect_vec_near(initial_omega(top, copy, VectorFrame::kBody), Eigen::Vector3d(0, 0, 120), 1e-9);
}

}  // namespace
}  // namespace tumble::app::viewer
