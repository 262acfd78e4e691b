// Roll-pitch-yaw both ways, including the gimbal-locked pitches +-pi/2 the principal frame of
// an -o rewrite can land on.
#include <gtest/gtest.h>

#include <numbers>

#include "app/robot/inertial_xml.hpp"

namespace tumble::app::robot {
namespace {

TEST(RollPitchYaw, ReadsBackTheSameRotation) {
  const double half = std::numbers::pi / 2;
  for (const Eigen::Vector3d& rpy :
       {Eigen::Vector3d(0.4, -0.7, 1.1), Eigen::Vector3d(-2.5, 1.2, -3.0),
        Eigen::Vector3d(0.3, half, 0.2), Eigen::Vector3d(0.3, -half, 0.2),
        Eigen::Vector3d(0, half, 0), Eigen::Vector3d(1.0, -half, -0.5),
        Eigen::Vector3d(0.7, half - 1e-9, -0.4), Eigen::Vector3d(-0.7, 1e-13 - half, 2.0),
        Eigen::Vector3d(2.0, half - 1e-6, 1.0)}) {
    const Eigen::Matrix3d rotation = rotation_from_rpy(rpy);
    const Eigen::Matrix3d back = rotation_from_rpy(roll_pitch_yaw(rotation));
    EXPECT_LE((back - rotation).norm(), 1e-15) << rpy.transpose();
  }
}

TEST(RollPitchYaw, AtGimbalLockTheRollIsZero) {
  const double half = std::numbers::pi / 2;
  const Eigen::Vector3d up = roll_pitch_yaw(rotation_from_rpy({0.3, half, 0.2}));
  EXPECT_NEAR(up.x(), 0.0, 1e-15);
  EXPECT_NEAR(up.z(), 0.2 - 0.3, 1e-15);
  const Eigen::Vector3d down = roll_pitch_yaw(rotation_from_rpy({0.3, -half, 0.2}));
  EXPECT_NEAR(down.x(), 0.0, 1e-15);
  EXPECT_NEAR(down.z(), 0.2 + 0.3, 1e-15);
}

}  // namespace
}  // namespace tumble::app::robot
