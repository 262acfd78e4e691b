#pragma once
// Private to the engine: the kick of the splitting family when a spring is damped.

#include "engine/body/rigid_body.hpp"

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

/// The half kick of the kick-drift-kick integrators (the splittings, free-rotor,
/// moser-veselov): v and world L from the forces and torques at `s`, exact for forces that
/// depend on x and q only. `damped` (non-null when the stepper found has_damping() true) takes
/// the exact flow of the velocity-dependent kick instead, reusing the flow it caches when the
/// kick repeats at the same x, q and step.
void kick(const BodyModel& body, BodyState& s, double half_step, KickFlowCache* damped);

}  // namespace tumble::engine::steppers
