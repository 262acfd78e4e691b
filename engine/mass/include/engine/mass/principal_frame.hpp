#pragma once
/// @file Principal moments and axes of an inertia tensor.

#include <optional>
#include <string>

#include <Eigen/Core>

namespace tumble::engine {

/// Principal moments in ascending order and the principal axes as the columns of a proper
/// rotation (det = +1) taking principal coordinates to the tensor's coordinates:
/// inertia = axes * diag(moments) * axes^T.
struct PrincipalFrame {
  Eigen::Vector3d moments = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
};

/// Diagonalises a symmetric inertia tensor. The sign of each of the first two axes is chosen
/// so its largest component is positive; the third completes a right-handed frame.
PrincipalFrame principal_frame(const Eigen::Matrix3d& inertia);

/// Why a triple of principal moments cannot belong to a rigid body (non-finite, not positive,
/// or breaking the triangle inequality I1 + I2 >= I3 beyond rounding), or nothing if it can.
std::optional<std::string> principal_moments_problem(const Eigen::Vector3d& moments);

}  // namespace tumble::engine
