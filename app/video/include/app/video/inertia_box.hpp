#pragma once
/// @file The box of equal inertia: the uniform solid box with a body's mass and principal
/// moments, along its principal axes at its centre of mass. Drawn by `tumble view` and
/// `tumble render` for a robot's stated and computed inertials, so that two inertials can be
/// compared by eye (a box's size, shape and orientation follow the tensor one to one).

#include <Eigen/Core>

#include "engine/mass/mass_properties.hpp"

namespace tumble::app {

/// A box placed in some frame: centre, axes (columns, a proper rotation) and full side lengths.
struct InertiaBox {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
  Eigen::Vector3d sides = Eigen::Vector3d::Zero();  ///< along axes.col(0..2), m
};

/// The box of `properties`' mass whose principal moments are its principal moments: with
/// moments I_i along the principal axes, I_i = m (a_j^2 + a_k^2) / 12 gives
/// a_i = sqrt(6 (I_j + I_k - I_i) / m). A side the moments make negative (an impossible
/// tensor, breaking the triangle inequality) or zero (a flat body) is 0. The mass must be
/// positive.
InertiaBox equal_inertia_box(const engine::MassProperties& properties);

}  // namespace tumble::app
