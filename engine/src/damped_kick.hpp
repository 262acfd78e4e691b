#pragma once
// Private to the engine: the kick of the splitting family when a spring is damped.

#include "engine/rigid_body.hpp"

namespace tumble::engine::steppers {

/// True when some spring of `body` has damping: its kick then depends on v and L.
bool has_damping(const BodyModel& body);

/// The exact flow over `t` (of either sign) of the kick sub-flow (x and q frozen, v and world
/// L moving) of a body with damped springs (engine/PHYSICS.md §3, "Splitting family").
void damped_kick(const BodyModel& body, BodyState& s, double t);

}  // namespace tumble::engine::steppers
