#include "app/viewer/viewer_initial_state.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <variant>

namespace tumble::app::viewer {
namespace {

constexpr double kDegrees = 180.0 / std::numbers::pi;

/// Gravity's acceleration on `body`, if it has any.
std::optional<Eigen::Vector3d> gravity_of(const engine::BodyModel& body) {
  for (const engine::ForceTerm& term : body.forces) {
    if (const auto* gravity = std::get_if<engine::Gravity>(&term)) return gravity->acceleration;
  }
  return std::nullopt;
}

/// Sets the world angular velocity: L = R J R^T w (principal frame R), pivot kinematics after.
void set_world_omega(const engine::BodyModel& body, engine::BodyState& state,
                     const Eigen::Vector3d& omega_world) {
  const Eigen::Vector3d local = state.orientation.conjugate() * omega_world;
  state.angular_momentum = state.orientation * Eigen::Vector3d(body.moments.cwiseProduct(local));
  engine::update_pivot_kinematics(body, state);
}

/// Unit "up" for a top (against gravity).
Eigen::Vector3d up_of(const engine::BodyModel& body) {
  return -gravity_of(body).value_or(Eigen::Vector3d(0.0, 0.0, -1.0)).normalized();
}

}  // namespace

Eigen::Vector3d initial_omega(const engine::BodyModel& body, const engine::BodyState& state,
                              VectorFrame frame) {
  const Eigen::Vector3d world = engine::angular_velocity(body, state);
  if (frame == VectorFrame::kWorld) return world;
  return engine::body_orientation(body, state).conjugate() * world;
}

void set_initial_omega(const engine::BodyModel& body, engine::BodyState& state,
                       const Eigen::Vector3d& omega, VectorFrame frame) {
  const Eigen::Vector3d world =
      frame == VectorFrame::kWorld ? omega
                                   : Eigen::Vector3d(engine::body_orientation(body, state) * omega);
  set_world_omega(body, state, world);
}

Eigen::Vector3d orientation_ypr_deg(const engine::BodyModel& body, const engine::BodyState& state) {
  // R = Rz(yaw) Ry(pitch) Rx(roll): R20 = -sin(pitch), R21 = cos(pitch) sin(roll),
  // R22 = cos(pitch) cos(roll), R10 = sin(yaw) cos(pitch), R00 = cos(yaw) cos(pitch).
  const Eigen::Matrix3d r = engine::body_orientation(body, state).toRotationMatrix();
  const double pitch = std::asin(std::clamp(-r(2, 0), -1.0, 1.0));
  double yaw = 0.0;
  double roll = 0.0;
  if (std::abs(r(2, 0)) < 1.0 - 1e-12) {
    yaw = std::atan2(r(1, 0), r(0, 0));
    roll = std::atan2(r(2, 1), r(2, 2));
  } else {
    // Gimbal lock: only yaw - roll (pitch = +90) or yaw + roll (pitch = -90) is defined; put
    // it all in yaw.
    yaw = std::atan2(-r(0, 1), r(1, 1));
  }
  return Eigen::Vector3d(yaw, pitch, roll) * kDegrees;
}

void set_orientation_ypr_deg(const engine::BodyModel& body, engine::BodyState& state,
                             const Eigen::Vector3d& ypr_deg) {
  const Eigen::Vector3d omega_body = initial_omega(body, state, VectorFrame::kBody);
  const Eigen::Vector3d a = ypr_deg / kDegrees;
  const Eigen::Quaterniond turn = Eigen::AngleAxisd(a[0], Eigen::Vector3d::UnitZ()) *
                                  Eigen::AngleAxisd(a[1], Eigen::Vector3d::UnitY()) *
                                  Eigen::AngleAxisd(a[2], Eigen::Vector3d::UnitX());
  state.orientation = (turn * body.principal_to_body).normalized();
  set_initial_omega(body, state, omega_body, VectorFrame::kBody);
}

void preset_principal_spin(const engine::BodyModel& body, engine::BodyState& state, int axis,
                           double rate, double perturbation) {
  if (axis < 0 || axis > 2) throw std::out_of_range("principal axis must be 0, 1 or 2");
  Eigen::Vector3d local = Eigen::Vector3d::Constant(perturbation * rate);
  local[axis] = rate;
  set_world_omega(body, state, state.orientation * local);
}

bool is_top(const engine::BodyModel& body) {
  return body.pivoted && gravity_of(body).has_value() && gravity_of(body)->squaredNorm() > 0.0 &&
         body.center_offset.squaredNorm() > 0.0;
}

TopPose top_pose(const engine::BodyModel& body, const engine::BodyState& state) {
  const Eigen::Vector3d axis = state.orientation * body.center_offset.normalized();
  const double cosine = std::clamp(axis.dot(up_of(body)), -1.0, 1.0);
  return {std::acos(cosine) * kDegrees, engine::angular_velocity(body, state).dot(axis)};
}

void set_top_pose(const engine::BodyModel& body, engine::BodyState& state, const TopPose& pose) {
  const Eigen::Vector3d up = up_of(body);
  // A horizontal axis to tilt about, up x (+x) (for gravity along -z that is +y), so that a
  // positive tilt leans the top towards +x.
  Eigen::Vector3d hinge = up.cross(Eigen::Vector3d::UnitX()).normalized();
  if (!hinge.allFinite() || hinge.squaredNorm() < 0.5) {
    hinge = up.cross(Eigen::Vector3d::UnitY()).normalized();
  }
  const Eigen::Vector3d local_axis = body.center_offset.normalized();
  // Keep the top's roll about its own axis: turn its current axis onto up, then tilt.
  const Eigen::Vector3d current_axis = state.orientation * local_axis;
  const Eigen::Quaterniond upright =
      Eigen::Quaterniond::FromTwoVectors(current_axis, up) * state.orientation;
  state.orientation =
      (Eigen::Quaterniond(Eigen::AngleAxisd(pose.tilt_deg / kDegrees, hinge)) * upright)
          .normalized();
  set_world_omega(body, state, pose.spin * (state.orientation * local_axis));
}

}  // namespace tumble::app::viewer
