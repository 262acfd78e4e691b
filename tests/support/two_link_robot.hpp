#pragma once
// A tiny two-link URDF of primitives for the robot picture's tests (render, viewer): a box base
// whose stated inertial is right and a cylinder arm whose stated inertia is wrong. The fixed
// joint is at the origin, so the links' frames are the model's; the geometry is placed by the
// links' own origins.

#include <Eigen/Core>

namespace tumble::testing {

/// The base: a 0.4 x 0.3 x 0.2 m box of 2.4 kg centred at (0, 0, 0.1), its stated inertial
/// exact: m/12 (b^2 + c^2, a^2 + c^2, a^2 + b^2) = (0.026, 0.04, 0.05).
inline const Eigen::Vector3d kTwoLinkBaseSize{0.4, 0.3, 0.2};
inline const Eigen::Vector3d kTwoLinkBaseCenter{0.0, 0.0, 0.1};
/// The arm: a cylinder of radius 0.05 m and length 0.5 m along z centred at (0.5, 0, 0.25),
/// 1 kg, stated inertia 0.01 I (wrong: the cylinder's is diag(0.0214583, 0.0214583, 0.00125)).
inline const Eigen::Vector3d kTwoLinkArmCenter{0.5, 0.0, 0.25};

inline constexpr const char* kTwoLinkUrdf = R"(<?xml version="1.0"?>
<robot name="two_link">
  <link name="base">
    <inertial>
      <origin xyz="0 0 0.1"/>
      <mass value="2.4"/>
      <inertia ixx="0.026" ixy="0" ixz="0" iyy="0.04" iyz="0" izz="0.05"/>
    </inertial>
    <visual>
      <origin xyz="0 0 0.1"/>
      <geometry><box size="0.4 0.3 0.2"/></geometry>
    </visual>
    <collision>
      <origin xyz="0 0 0.1"/>
      <geometry><box size="0.4 0.3 0.2"/></geometry>
    </collision>
  </link>
  <link name="arm">
    <inertial>
      <origin xyz="0.5 0 0.25"/>
      <mass value="1"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>
    </inertial>
    <collision>
      <origin xyz="0.5 0 0.25"/>
      <geometry><cylinder radius="0.05" length="0.5"/></geometry>
    </collision>
  </link>
  <joint name="fixed" type="fixed">
    <parent link="base"/>
    <child link="arm"/>
    <origin xyz="0 0 0"/>
  </joint>
</robot>
)";

}  // namespace tumble::testing
