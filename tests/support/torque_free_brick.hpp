#pragma once
// The bench and stability jobs' shared case: a free brick tumbling near its intermediate axis
// (torque-free), and the error of a simulate-library run of it against the engine's exact
// torque-free solution, the oracle both jobs' rows are checked against.

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "app/analysis/simulation_run.hpp"
#include "engine/simulation/reference_motion.hpp"
#include "support/scene_builder.hpp"

namespace tumble::testing {

/// A free asymmetric body tumbling near its intermediate axis, torque-free: 0.5 s at dt 0.01
/// with rk4.
inline nlohmann::json torque_free_brick_scene() {
  return SceneBuilder()
      .duration(0.5)
      .dt(0.01)
      .integrator("rk4")
      .body(BodyBuilder("brick").angular_velocity({0.01, 3.0, 0.01}, "body"))
      .json();
}

/// The geodesic angle at the end between a run of `integrator` at `dt` of `scene` (made by the
/// simulate library, neither the bench nor the stability job) and the engine's exact
/// torque-free solution.
inline double exact_final_error(const std::filesystem::path& scene, const std::string& integrator,
                                double dt) {
  app::SimulateOptions options;
  options.scene = scene;
  options.integrator = integrator;
  options.dt = dt;
  const app::Trajectory trajectory = app::run_simulation(options);
  const engine::ReferenceMotion exact(trajectory.bodies, trajectory.states.front());
  return engine::orientation_angle(exact.at(trajectory.times.back()).front().orientation,
                                   trajectory.states.back().front().orientation);
}

}  // namespace tumble::testing
