// Inertial elements (app/robot/inertial_xml.cpp): numbers that read back exactly, roll-pitch-yaw
// that rebuilds its rotation, and the three formats' layout.
#include "app/robot/inertial_xml.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <random>

namespace tumble::app::robot {
namespace {

using ::testing::HasSubstr;

TEST(InertialXml, NumbersAreShortestAndReadBack) {
  EXPECT_EQ(xml_number(0.25), "0.25");
  EXPECT_EQ(xml_number(1e-7), "1e-07");
  EXPECT_EQ(xml_number(0.1), "0.1");
  EXPECT_EQ(xml_number(-0.0), "0");
  EXPECT_EQ(xml_number(-3.0), "-3");
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> exponent(-300.0, 300.0);
  for (int i = 0; i < 2000; ++i) {
    const double value = (i % 2 ? -1.0 : 1.0) * std::pow(10.0, exponent(random));
    EXPECT_EQ(std::strtod(xml_number(value).c_str(), nullptr), value) << xml_number(value);
  }
}

TEST(InertialXml, RollPitchYawFollowsUrdfsConvention) {
  // R = Rz(yaw) Ry(pitch) Rx(roll): rotations about the fixed x, then y, then z axes.
  const Eigen::Vector3d rpy(0.3, -0.4, 1.2);
  const Eigen::Matrix3d expected = (Eigen::AngleAxisd(1.2, Eigen::Vector3d::UnitZ()) *
                                    Eigen::AngleAxisd(-0.4, Eigen::Vector3d::UnitY()) *
                                    Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()))
                                       .toRotationMatrix();
  EXPECT_TRUE(rotation_from_rpy(rpy).isApprox(expected, 1e-15));
  EXPECT_LT((roll_pitch_yaw(expected) - rpy).norm(), 1e-15);
}

/// rotation_from_rpy(roll_pitch_yaw(R)) == R to rounding, `rotation` given by its rpy.
void expect_rebuilt(const Eigen::Matrix3d& rotation) {
  const Eigen::Vector3d rpy = roll_pitch_yaw(rotation);
  EXPECT_LT((rotation_from_rpy(rpy) - rotation).cwiseAbs().maxCoeff(), 1e-14)
      << "rpy " << rpy.transpose() << "\nof\n"
      << rotation;
}

TEST(InertialXml, RollPitchYawRebuildsAnyRotation) {
  std::mt19937_64 random(11);
  std::normal_distribution<double> normal;
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Quaterniond q(normal(random), normal(random), normal(random), normal(random));
    expect_rebuilt(q.normalized().toRotationMatrix());
  }
}

TEST(InertialXml, RollPitchYawRebuildsRotationsAtAndNearGimbalLock) {
  constexpr double kHalfPi = std::numbers::pi / 2;
  for (const double sign : {1.0, -1.0}) {
    for (const double off : {0.0, 1e-15, 1e-12, 1e-9, 1e-7, 1e-5, 1e-3}) {
      expect_rebuilt(rotation_from_rpy({0.3, sign * (kHalfPi - off), 0.5}));
      expect_rebuilt(rotation_from_rpy({-2.0, sign * (kHalfPi - off), 1.0}));
    }
  }
  // Exactly at the lock, a principal frame turned a quarter about y: roll is taken as zero.
  Eigen::Matrix3d quarter;
  quarter << 0, 0, 1, 0, 1, 0, -1, 0, 0;
  EXPECT_LT((roll_pitch_yaw(quarter) - Eigen::Vector3d(0, kHalfPi, 0)).norm(), 1e-15);
}

engine::MassProperties turned_body() {
  engine::MassProperties p;
  p.mass = 2.5;
  p.center_of_mass = {0.1, -0.2, 0.3};
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.9, Eigen::Vector3d(1, 1, -2).normalized()).toRotationMatrix();
  p.inertia = R * Eigen::Vector3d(0.1, 0.2, 0.25).asDiagonal() * R.transpose();
  return p;
}

TEST(InertialXml, ElementsPlaceTheirLinesWithIndentAndStep) {
  const std::string urdf =
      inertial_element(RobotFormat::urdf, turned_body(), InertialFrame::mesh, "    ", "\t");
  EXPECT_EQ(urdf.rfind("<inertial>\n    \t<origin xyz=\"0.1 -0.2 0.3\" rpy=\"0 0 0\"/>\n", 0), 0u)
      << urdf;
  EXPECT_THAT(urdf, HasSubstr("\n    \t<mass value=\"2.5\"/>\n"));
  EXPECT_TRUE(urdf.ends_with("\n    </inertial>")) << urdf;
  const std::string sdf =
      inertial_element(RobotFormat::sdf, turned_body(), InertialFrame::mesh, "  ", "  ");
  EXPECT_THAT(sdf, HasSubstr("\n    <pose>0.1 -0.2 0.3 0 0 0</pose>\n"));
  EXPECT_THAT(sdf, HasSubstr("\n      <ixx>"));
  EXPECT_TRUE(sdf.ends_with("\n    </inertia>\n  </inertial>")) << sdf;
  const std::string mjcf =
      inertial_element(RobotFormat::mjcf, turned_body(), InertialFrame::mesh, "  ", "  ");
  EXPECT_EQ(mjcf.find('\n'), std::string::npos);
  EXPECT_EQ(mjcf.rfind("<inertial pos=\"0.1 -0.2 0.3\" mass=\"2.5\" fullinertia=\"", 0), 0u);
}

}  // namespace
}  // namespace tumble::app::robot
