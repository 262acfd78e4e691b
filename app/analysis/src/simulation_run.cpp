// A run of a scene without rendering (simulation_run.hpp): the command's options over the
// scene, the stepping loop with its recorded steps and each body's invariants.
#include "app/analysis/simulation_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "app/analysis/blow_up.hpp"
#include "app/support/printf_number.hpp"
#include "base/errors.hpp"
#include "engine/dynamics/integrators.hpp"
#include "engine/simulation/reference_motion.hpp"
#include "engine/simulation/simulation.hpp"

namespace tumble::app {
namespace {

using tumble::InputError;

/// Applies the options on top of the scene and checks them all.
void apply_run_options(const SimulateOptions& options, SceneDescription& scene) {
  if (options.integrator) override_integrator(scene, *options.integrator);
  if (options.dt) scene.dt = positive_option(*options.dt, "--dt");
  if (options.duration) scene.duration = positive_option(*options.duration, "--duration");
  if (options.tolerance) scene.tolerance = positive_option(*options.tolerance, "--tolerance");
  if (options.absolute_tolerance) {
    if (!(std::isfinite(*options.absolute_tolerance) && *options.absolute_tolerance >= 0.0)) {
      throw InputError("--absolute-tolerance: expected a finite number >= 0, got " +
                       printf_number(*options.absolute_tolerance, "%.17g"));
    }
    scene.absolute_tolerance = *options.absolute_tolerance;
  }
  if (auto problem = step_problem(scene.dt, scene.duration)) {
    throw InputError((options.dt ? std::string("--dt") : scene.file.string() + ": dt") + ": " +
                     *problem);
  }
  if (options.every < 1) {
    throw InputError("--every: expected a whole number >= 1, got " + std::to_string(options.every));
  }
  if (options.blowup_factor &&
      !(positive_option(*options.blowup_factor, "--blowup-factor") > 1.0)) {
    throw InputError("--blowup-factor: expected a growth factor > 1, got " +
                     printf_number(*options.blowup_factor, "%.17g"));
  }
}

/// Refuses, unless --allow-long, a run of more than kMaxStepsWithoutAllowLong steps or a CSV
/// estimated beyond kMaxCsvBytes, saying how many.
void check_run_length(const SimulateOptions& options, const SceneDescription& scene) {
  if (options.allow_long) return;
  const double steps = std::ceil(scene.duration / scene.dt);
  const std::string what = printf_number(steps, "%.3g") + " steps (duration " +
                           printf_number(scene.duration) + " s / dt " + printf_number(scene.dt) +
                           " s)";
  if (steps > kMaxStepsWithoutAllowLong) {
    throw InputError((options.dt ? std::string("--dt") : scene.file.string() + ": dt") + ": " +
                     what + ", more than " + printf_number(kMaxStepsWithoutAllowLong, "%.0e") +
                     "; give --allow-long to run it");
  }
  const double rows = (std::floor(steps / static_cast<double>(options.every)) + 2.0) *
                      static_cast<double>(scene.bodies.size());
  if (options.csv && rows * kCsvRowBytes > kMaxCsvBytes) {
    throw InputError("--csv: " + what + " write about " + printf_number(rows, "%.3g") + " rows, " +
                     printf_number(rows * kCsvRowBytes / 1e9, "%.3g") + " GB, more than " +
                     printf_number(kMaxCsvBytes / 1e9, "%.3g") +
                     " GB; give --every N or --allow-long");
  }
}

/// Relative drift |value - initial| / |initial|, or absolute when the initial value is zero.
double invariant_drift(double value, double initial) {
  const double change = std::abs(value - initial);
  return initial != 0.0 ? change / std::abs(initial) : change;
}

/// Watches one body's energy and |L| over a run.
struct InvariantMonitor {
  double energy0 = 0.0;
  double momentum0 = 0.0;
  double energy_max = 0.0;
  double momentum_max = 0.0;
  double energy_final = 0.0;
  double momentum_final = 0.0;

  explicit InvariantMonitor(const engine::Invariants& start)
      : energy0(start.energy), momentum0(start.momentum) {}

  void observe(const engine::Invariants& now) {
    energy_final = invariant_drift(now.energy, energy0);
    momentum_final = invariant_drift(now.momentum, momentum0);
    energy_max = std::max(energy_max, energy_final);
    momentum_max = std::max(momentum_max, momentum_final);
  }
};

/// The geodesic angle between the body's orientation and its exact solution at the
/// simulation's time (torque-free, or a heavy symmetric top), or nothing when none applies.
std::optional<double> exact_orientation_error(const engine::BodyModel& body,
                                              const engine::BodyState& initial,
                                              const engine::BodyState& state, double time) {
  if (!body.torque_free() && !engine::is_lagrange_top(body)) return std::nullopt;
  try {
    const engine::ReferenceMotion exact({body}, {initial});  // exact: checked just above
    return engine::orientation_angle(exact.at(time).front().orientation, state.orientation);
  } catch (const InputError&) {  // an inertia the exact solution cannot take
    return std::nullopt;
  }
}

/// The compiled scene as a simulation, with --blowup-factor over the scene's. Throws
/// tumble::InputError naming the scene file when the integrator cannot handle a body.
engine::Simulation build_simulation(const SimulateOptions& options, const SceneDescription& scene) {
  CompiledScene compiled = compile_scene(scene);
  engine::SimulationSettings settings = compiled.settings;
  if (options.blowup_factor) settings.blowup_factor = *options.blowup_factor;
  try {
    return engine::Simulation(std::move(compiled.bodies), std::move(compiled.initial), settings);
  } catch (const InputError& error) {  // e.g. the exact integrator on a body with torques
    throw InputError(scene.file.string() + ": " + error.what());
  }
}

/// Steps to the end or the blow-up, watching each body's invariants every step and recording
/// every `every`th step (and the first and the last), until `stop` says so. Returns the time
/// spent in the steps alone, or nothing when stopped.
std::optional<std::chrono::steady_clock::duration> step_and_record(
    engine::Simulation& simulation, std::vector<InvariantMonitor>& monitors, std::size_t every,
    const RecordStep& record, const StopRequested& stop) {
  const auto& bodies = simulation.bodies();
  record(simulation);
  std::size_t last_recorded = 0;
  std::chrono::steady_clock::duration stepping{};
  while (!simulation.finished()) {
    if (simulation.steps() % 64 == 0 && stop()) return std::nullopt;
    const auto start = std::chrono::steady_clock::now();
    const bool good = simulation.step();
    stepping += std::chrono::steady_clock::now() - start;
    if (!good) break;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      monitors[i].observe(engine::invariants(bodies[i], simulation.states()[i]));
    }
    if (simulation.steps() % every == 0 || simulation.finished()) {
      record(simulation);
      last_recorded = simulation.steps();
    }
  }
  // After a blow-up the states are the last good ones: make sure that row is recorded.
  if (simulation.steps() != last_recorded && simulation.steps() > 0) record(simulation);
  return stepping;
}

/// Each body's drifts and its orientation error against its exact solution (torque-free or a
/// heavy symmetric top).
std::vector<BodySummary> body_summaries(const engine::Simulation& simulation,
                                        const std::vector<InvariantMonitor>& monitors) {
  const auto& bodies = simulation.bodies();
  std::vector<BodySummary> summaries;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    BodySummary body;
    body.name = bodies[i].name;
    body.energy_conserved = bodies[i].conservative();
    body.momentum_conserved = bodies[i].torque_free();
    body.energy_drift_max = monitors[i].energy_max;
    body.energy_drift_final = monitors[i].energy_final;
    body.momentum_drift_max = monitors[i].momentum_max;
    body.momentum_drift_final = monitors[i].momentum_final;
    body.orientation_error = exact_orientation_error(bodies[i], simulation.initial_states()[i],
                                                     simulation.states()[i], simulation.time());
    summaries.push_back(body);
  }
  return summaries;
}

}  // namespace

SimulationRun::SimulationRun(const SimulateOptions& options, SceneDescription scene)
    : options_(options), scene_(std::move(scene)) {
  apply_run_options(options_, scene_);
  check_run_length(options_, scene_);
}

bool SimulationRun::run(const RecordStep& record, const StopRequested& stop) {
  engine::Simulation simulation = build_simulation(options_, scene_);
  summary_ = RunSummary{};
  summary_.scene = scene_.name;
  summary_.file = scene_.file;
  summary_.integrator = scene_.integrator;
  summary_.dt = simulation.settings().dt;
  summary_.duration = simulation.settings().duration;
  summary_.total_steps = simulation.total_steps();
  std::vector<InvariantMonitor> monitors;
  for (std::size_t i = 0; i < simulation.bodies().size(); ++i) {
    monitors.emplace_back(
        engine::invariants(simulation.bodies()[i], simulation.initial_states()[i]));
  }
  const auto stepping =
      step_and_record(simulation, monitors, static_cast<std::size_t>(options_.every), record, stop);
  if (!stepping) return false;
  summary_.steps = simulation.steps();
  summary_.time = simulation.time();
  summary_.wall_seconds = std::chrono::duration<double>(*stepping).count();
  summary_.bodies = body_summaries(simulation, monitors);
  if (simulation.blow_up()) summary_.blow_up = "blow-up: " + describe_blow_up(simulation);
  return true;
}

nlohmann::json integrators_to_json() {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& info : engine::integrator_catalog()) {
    list.push_back({{"name", info.name},
                    {"order", info.order},
                    {"adaptive", info.adaptive},
                    {"needs_torque_free", info.needs_torque_free},
                    {"properties", info.properties}});
  }
  return list;
}

nlohmann::json summary_to_json(const RunSummary& summary) {
  nlohmann::json bodies = nlohmann::json::array();
  for (const BodySummary& body : summary.bodies) {
    bodies.push_back({
        {"name", body.name},
        {"energy_conserved", body.energy_conserved},
        {"momentum_conserved", body.momentum_conserved},
        {"energy_drift", {{"max", body.energy_drift_max}, {"final", body.energy_drift_final}}},
        {"momentum_drift",
         {{"max", body.momentum_drift_max}, {"final", body.momentum_drift_final}}},
        {"orientation_error",
         body.orientation_error ? nlohmann::json(*body.orientation_error) : nlohmann::json()},
    });
  }
  return {
      {"scene", summary.scene},
      {"file", summary.file.string()},
      {"integrator", summary.integrator},
      {"dt", summary.dt},
      {"duration", summary.duration},
      {"steps", summary.steps},
      {"total_steps", summary.total_steps},
      {"time", summary.time},
      {"wall_seconds", summary.wall_seconds},
      {"steps_per_second", summary.wall_seconds > 0.0
                               ? static_cast<double>(summary.steps) / summary.wall_seconds
                               : 0.0},
      {"csv", summary.csv ? nlohmann::json(summary.csv->string()) : nlohmann::json()},
      {"csv_rows", summary.csv_rows},
      {"completed", !summary.blow_up.has_value()},
      {"blow_up", summary.blow_up ? nlohmann::json(*summary.blow_up) : nlohmann::json()},
      {"bodies", bodies},
  };
}

}  // namespace tumble::app
