#pragma once
/// @file How every command names a run's blow-up.

#include <string>

namespace tumble::engine {
class Simulation;
}  // namespace tumble::engine

namespace tumble::app {

/// "body 'NAME' at step N (t = T s): REASON" (empty when `simulation` has not blown up).
std::string describe_blow_up(const engine::Simulation& simulation);

}  // namespace tumble::app
