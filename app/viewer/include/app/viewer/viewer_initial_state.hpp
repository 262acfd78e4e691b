#pragma once
/// @file Editing a body's initial state the way the viewer's panel shows it: angular velocity in
/// the world or the body frame, orientation as yaw, pitch and roll, a top's tilt and spin, and
/// the "spin about principal axis k with a small perturbation" presets. Every setter keeps the
/// engine's state consistent (world angular momentum from w, pivot kinematics).

#include <Eigen/Core>
#include <cstddef>

#include "app/scene/scene.hpp"
#include "engine/body/rigid_body.hpp"

namespace tumble::app::viewer {

/// Angular velocity (rad/s) of `state` in `frame`: world axes, or the body's own axes (the
/// mesh's, as scene files write body-frame vectors).
Eigen::Vector3d initial_omega(const engine::BodyModel& body, const engine::BodyState& state,
                              VectorFrame frame);

/// Sets the angular velocity to `omega` (rad/s, in `frame`): world L = R J R^T w about the
/// rotation centre; a pivoted body's centre of mass velocity follows.
void set_initial_omega(const engine::BodyModel& body, engine::BodyState& state,
                       const Eigen::Vector3d& omega, VectorFrame frame);

/// The body frame's orientation as intrinsic z-y'-x'' angles (yaw, pitch, roll) in degrees:
/// body-to-world rotation Rz(yaw) Ry(pitch) Rx(roll). Pitch in [-90, 90].
Eigen::Vector3d orientation_ypr_deg(const engine::BodyModel& body, const engine::BodyState& state);

/// Turns the body to yaw, pitch, roll (degrees) keeping its body-frame angular velocity (it
/// keeps spinning about the same body axis). A pivoted body turns about its pivot.
void set_orientation_ypr_deg(const engine::BodyModel& body, engine::BodyState& state,
                             const Eigen::Vector3d& ypr_deg);

/// Sets w to spin about principal axis `axis` (0, 1 or 2: smallest to largest moment) at
/// `rate` rad/s, plus `perturbation` * rate about each of the other two axes, so that an
/// intermediate-axis spin shows its flip. Throws std::out_of_range for a bad axis.
void preset_principal_spin(const engine::BodyModel& body, engine::BodyState& state, int axis,
                           double rate, double perturbation);

/// A top: a pivoted body whose centre of mass is off the pivot, under gravity.
bool is_top(const engine::BodyModel& body);

/// Tilt (degrees, of the top's axis from the upward vertical) and spin (rad/s, w along that
/// axis). The top's axis runs from the pivot through the centre of mass; "up" is against
/// gravity.
struct TopPose {
  double tilt_deg = 0.0;
  double spin = 0.0;
};
TopPose top_pose(const engine::BodyModel& body, const engine::BodyState& state);

/// Stands the top at `pose`: its axis tilted from up by tilt_deg towards world +x (about the
/// horizontal axis up x (+x)), keeping its roll about its own axis, spinning about that axis at
/// `spin` rad/s with no other angular velocity. Requires is_top(body).
void set_top_pose(const engine::BodyModel& body, engine::BodyState& state, const TopPose& pose);

}  // namespace tumble::app::viewer
