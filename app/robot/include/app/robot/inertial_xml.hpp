#pragma once
/// @file Inertial elements as URDF, SDF and MJCF write them, from mass properties in a link's
/// frame.
///
/// Sign convention: all three formats take the elements of the inertia tensor, so the
/// products of inertia are ixy = -∫ x y dm (and so on), exactly engine::MassProperties'
/// off-diagonal entries. MJCF's fullinertia lists them in MuJoCo's order
/// "ixx iyy izz ixy ixz iyz". Numbers are written in the shortest form that reads back to
/// the same double, so a file rewritten by `tumble inertials -o` checks with zero difference.

#include <string>

#include <Eigen/Core>

#include "app/robot/robot_model.hpp"
#include "engine/mass/mass_properties.hpp"

namespace tumble::app::robot {

/// How the inertia is written: in the link's (mesh file's) axes, rotation zero and all six
/// elements; or in the principal frame, with the rotation of the principal axes (URDF/SDF
/// roll-pitch-yaw, MJCF quat) and only the three principal moments.
enum class InertialFrame { mesh, principal };

/// The element for `properties` (centre of mass and inertia in the link's frame). Its first
/// line has no indentation (the caller places it); every further line starts with `indent`,
/// children with `indent` + `step`. Lines are joined with "\n".
std::string inertial_element(RobotFormat format, const engine::MassProperties& properties,
                             InertialFrame frame, const std::string& indent = "",
                             const std::string& step = "  ");

/// The shortest decimal that reads back as `value` ("0.25", "1e-07"); -0 is written "0".
std::string xml_number(double value);

/// Roll, pitch, yaw (URDF and SDF: fixed axes x, then y, then z, R = Rz(yaw) Ry(pitch)
/// Rx(roll)) of a rotation matrix, rebuilding it to rounding at any pitch; at pitch +-pi/2
/// the roll is taken as zero.
Eigen::Vector3d roll_pitch_yaw(const Eigen::Matrix3d& rotation);

/// The rotation of roll, pitch, yaw (the inverse of roll_pitch_yaw).
Eigen::Matrix3d rotation_from_rpy(const Eigen::Vector3d& rpy);

}  // namespace tumble::app::robot
