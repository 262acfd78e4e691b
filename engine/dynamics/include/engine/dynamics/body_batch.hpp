#pragma once
/// @file Many free bodies stepped together: structure of arrays, one plain loop per step.
///
/// For scenes with thousands of torque-free bodies under uniform gravity (debris, particles with
/// orientation) the per-body virtual stepper and the Eigen quaternion temporaries cost more
/// than the arithmetic. Here each component lives in its own contiguous array and the step is
/// one branch-free loop over bodies with no calls but sqrt, sin and cos. Under the project's
/// flags GCC still keeps it scalar (sqrt may set errno; sin and cos have no vector variants
/// without -ffast-math); the layout is ready for a vector math library.

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "engine/body/rigid_body.hpp"

namespace tumble::engine {

/// Free bodies (no pivot, no torque), each component in its own contiguous array; index i of
/// every array belongs to body i.
struct FreeBodyBatch {
  std::vector<double> position_x, position_y, position_z;  ///< centre of mass, world, m
  std::vector<double> velocity_x, velocity_y, velocity_z;  ///< m/s
  std::vector<double> orientation_w, orientation_x, orientation_y,
      orientation_z;                                       ///< principal to world
  std::vector<double> momentum_x, momentum_y, momentum_z;  ///< world angular momentum, kg m^2/s
  std::vector<double> inverse_moment_1, inverse_moment_2,
      inverse_moment_3;  ///< 1 / principal moments

  std::size_t size() const { return position_x.size(); }
  /// Appends a body with principal `moments` (positive; throws std::invalid_argument otherwise)
  /// in `state` (its orientation is stored normalised).
  void add(const Eigen::Vector3d& moments, const BodyState& state);
  /// Body i as a BodyState.
  BodyState state(std::size_t i) const;
};

/// One step of semi-implicit (symplectic) Euler for every body of the batch, the scheme of the
/// scalar "semi-implicit-euler" stepper under uniform gravity: v += h g, x += h v, then the
/// free rotation as the principal-axis sub-rotations R1(h) R2(h) R3(h) (engine/PHYSICS.md §3;
/// world L is constant without torque), normalised.
void step_semi_implicit_euler(FreeBodyBatch& batch, const Eigen::Vector3d& gravity, double h);

}  // namespace tumble::engine
