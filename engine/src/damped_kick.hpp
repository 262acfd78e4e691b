#pragma once
// Private to the engine: the kick of the splitting family when a spring is damped.

#include "engine/rigid_body.hpp"

namespace tumble::engine::steppers {

/// True when some spring of `body` has damping: its kick then depends on v and L.
bool has_damping(const BodyModel& body);

/// The last flow of damped_kick(): the next kick at the same x, q and t (the closing half kick
/// of a fixed step and the opening one of the next) reuses it instead of a new exponential.
struct KickFlowCache {
  bool valid = false;
  Eigen::Vector3d position;
  Eigen::Vector4d orientation;
  double t = 0.0;
  Eigen::Matrix<double, 7, 7> flow;  ///< the augmented flow; its top-left 4 x 4 when pivoted
};

/// The exact flow over `t` (of either sign) of the kick sub-flow (x and q frozen, v and world
/// L moving) of a body with damped springs (engine/PHYSICS.md §3, "Splitting family").
void damped_kick(const BodyModel& body, BodyState& s, double t, KickFlowCache* cache = nullptr);

}  // namespace tumble::engine::steppers
