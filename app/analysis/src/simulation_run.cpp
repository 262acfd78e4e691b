// A scene run without rendering: options over the scene, the run with its invariants watched,
// its rows recorded into the trajectory CSV or into memory, and the summary.
#include "app/analysis/simulation_run.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <sstream>

#include "app/analysis/blow_up.hpp"
#include "app/scene/scene.hpp"
#include "app/support/csv_writer.hpp"
#include "app/support/exit_status.hpp"
#include "app/support/printf_number.hpp"
#include "base/errors.hpp"
#include "engine/dynamics/integrators.hpp"
#include "engine/simulation/reference_motion.hpp"
#include "engine/simulation/simulation.hpp"

namespace tumble::app {
namespace {

using tumble::InputError;

/// Applies the command-line options on top of the scene and checks them all.
void apply_options(const SimulateOptions& options, SceneDescription& scene) {
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

/// Where a run's recorded rows go: the CSV, or the trajectory in memory.
using RowRecorder = std::function<void(double time, const std::vector<engine::BodyModel>& bodies,
                                       const std::vector<engine::BodyState>& states)>;

/// Steps to the end or the blow-up, watching each body's invariants every step and recording
/// every `every`th step (and the first and the last) with `record`, until `interrupted` says
/// so. Returns the time spent in the steps alone.
std::chrono::steady_clock::duration run_and_record(engine::Simulation& simulation,
                                                   std::vector<InvariantMonitor>& monitors,
                                                   const RowRecorder& record, std::size_t every,
                                                   const std::function<bool()>& interrupted) {
  const auto& bodies = simulation.bodies();
  record(simulation.time(), bodies, simulation.states());
  std::size_t last_written = 0;
  std::chrono::steady_clock::duration stepping{};
  while (!simulation.finished()) {
    if (simulation.steps() % 64 == 0 && interrupted && interrupted()) return stepping;
    const auto start = std::chrono::steady_clock::now();
    const bool good = simulation.step();
    stepping += std::chrono::steady_clock::now() - start;
    if (!good) break;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      monitors[i].observe(engine::invariants(bodies[i], simulation.states()[i]));
    }
    if (simulation.steps() % every == 0 || simulation.finished()) {
      record(simulation.time(), bodies, simulation.states());
      last_written = simulation.steps();
    }
  }
  // After a blow-up the states are the last good ones: make sure that row is recorded.
  if (simulation.steps() != last_written && simulation.steps() > 0) {
    record(simulation.time(), bodies, simulation.states());
  }
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

/// `scene` with the options applied, checked (InputError naming the file or option).
SceneDescription checked_scene(const SimulateOptions& options, SceneDescription scene) {
  apply_options(options, scene);
  check_run_length(options, scene);
  return scene;
}

/// The checked scene of `options` (InputError naming the file or option).
SceneDescription checked_scene(const SimulateOptions& options) {
  return checked_scene(options, load_scene(options.scene));
}

/// Runs `scene` (compiled here: meshes imported) recording rows with `record`, and fills
/// `summary` but for the CSV; returns false when
/// `interrupted` stopped it.
bool run_scene(const SimulateOptions& options, const SceneDescription& scene,
               const RowRecorder& record, const std::function<bool()>& interrupted,
               RunSummary& summary) {
  engine::Simulation simulation = build_simulation(options, scene);
  summary.scene = scene.name;
  summary.file = scene.file;
  summary.integrator = scene.integrator;
  summary.dt = simulation.settings().dt;
  summary.duration = simulation.settings().duration;
  summary.total_steps = simulation.total_steps();
  std::vector<InvariantMonitor> monitors;
  for (std::size_t i = 0; i < simulation.bodies().size(); ++i) {
    monitors.emplace_back(
        engine::invariants(simulation.bodies()[i], simulation.initial_states()[i]));
  }
  const auto stepping = run_and_record(simulation, monitors, record,
                                       static_cast<std::size_t>(options.every), interrupted);
  if (interrupted && interrupted()) return false;
  summary.steps = simulation.steps();
  summary.time = simulation.time();
  summary.wall_seconds = std::chrono::duration<double>(stepping).count();
  summary.bodies = body_summaries(simulation, monitors);
  if (simulation.blow_up()) summary.blow_up = "blow-up: " + describe_blow_up(simulation);
  return true;
}

}  // namespace

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

void list_integrators(bool as_json, std::ostream& out) {
  const auto& catalog = engine::integrator_catalog();
  if (as_json) {
    out << integrators_to_json().dump(2) << "\n";
    return;
  }
  std::size_t width = 4;
  for (const auto& info : catalog) width = std::max(width, info.name.size());
  const auto pad = [](std::string text, std::size_t size) {
    text.resize(std::max(size, text.size()), ' ');
    return text;
  };
  out << pad("name", width + 2) << pad("order", 7) << "properties\n";
  for (const auto& info : catalog) {
    const std::string order = info.order < 0 ? "exact" : std::to_string(info.order);
    out << pad(info.name, width + 2) << pad(order, 7) << info.properties << "\n";
  }
}

BodySample Trajectory::sample(std::size_t k, std::size_t body) const {
  const engine::BodyModel& model = bodies.at(body);
  const engine::BodyState& state = states.at(k).at(body);
  return {state.position,         engine::body_orientation(model, state),
          state.velocity,         engine::angular_velocity(model, state),
          state.angular_momentum, engine::energy(model, state)};
}

Trajectory run_simulation(const SimulateOptions& options,
                          const std::function<bool()>& interrupted) {
  return run_simulation(options, load_scene(options.scene), interrupted);
}

Trajectory run_simulation(const SimulateOptions& options, SceneDescription loaded,
                          const std::function<bool()>& interrupted) {
  const SceneDescription scene = checked_scene(options, std::move(loaded));
  Trajectory trajectory;
  trajectory.inputs = scene_inputs(scene);
  const RowRecorder record = [&](double time, const std::vector<engine::BodyModel>& bodies,
                                 const std::vector<engine::BodyState>& states) {
    if (trajectory.bodies.empty()) trajectory.bodies = bodies;
    trajectory.times.push_back(time);
    trajectory.states.push_back(states);
  };
  run_scene(options, scene, record, interrupted, trajectory.summary);
  return trajectory;
}

void write_trajectory_csv(const Trajectory& trajectory, const std::filesystem::path& path) {
  TrajectoryCsv csv(path, trajectory.inputs);
  for (std::size_t k = 0; k < trajectory.times.size(); ++k) {
    csv.write_rows(trajectory.times[k], trajectory.bodies, trajectory.states[k]);
  }
  csv.commit();
}

int simulate_scene(const SimulateOptions& options, const std::function<bool()>& interrupted,
                   RunSummary& summary, std::ostream& err) {
  // Scene and options: everything is checked before any output is created.
  const SceneDescription scene = checked_scene(options);
  // The CSV's temporary file is created now, so an unwritable path fails before the run.
  std::optional<TrajectoryCsv> csv;
  if (options.csv) csv.emplace(*options.csv, scene_inputs(scene));
  const RowRecorder record = [&](double time, const std::vector<engine::BodyModel>& bodies,
                                 const std::vector<engine::BodyState>& states) {
    if (csv) csv->write_rows(time, bodies, states);
  };
  // the CSV's temporary goes with `csv`
  if (!run_scene(options, scene, record, interrupted, summary)) return kExitInterrupted;
  if (csv) {
    csv->commit();
    summary.csv = csv->path();
    summary.csv_rows = csv->rows();
  }
  if (summary.blow_up) {
    if (csv) {
      *summary.blow_up += "; " + csv->path().string() +
                          " holds the rows up to t = " + printf_number(summary.time, "%.9g") + " s";
    }
    err << "tumble simulate: " << *summary.blow_up << "\n";
    return kExitBlowUp;
  }
  return 0;
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

std::string format_summary(const RunSummary& summary) {
  std::ostringstream out;
  out << summary.scene << ": " << summary.integrator << ", dt " << printf_number(summary.dt)
      << " s, " << summary.steps << " of " << summary.total_steps
      << " steps to t = " << printf_number(summary.time) << " s"
      << (summary.blow_up ? " (blew up)" : "") << "\n";
  const double rate =
      summary.wall_seconds > 0.0 ? static_cast<double>(summary.steps) / summary.wall_seconds : 0.0;
  out << "  stepping " << printf_number(summary.wall_seconds, "%.3g") << " s wall, "
      << printf_number(rate, "%.3g") << " steps/s\n";
  for (const BodySummary& body : summary.bodies) {
    out << "  body '" << body.name << "'\n";
    out << "    energy drift   max " << printf_number(body.energy_drift_max, "%.3e") << "  final "
        << printf_number(body.energy_drift_final, "%.3e")
        << (body.energy_conserved ? "" : "  (not an invariant here)") << "\n";
    out << "    |L| drift      max " << printf_number(body.momentum_drift_max, "%.3e") << "  final "
        << printf_number(body.momentum_drift_final, "%.3e")
        << (body.momentum_conserved ? "" : "  (not an invariant here: torques)") << "\n";
    if (body.orientation_error) {
      out << "    orientation error " << printf_number(*body.orientation_error, "%.3e")
          << " rad against the exact " << (body.momentum_conserved ? "torque-free" : "heavy-top")
          << " solution\n";
    }
  }
  if (summary.csv) {
    out << "  csv " << summary.csv->string() << " (" << summary.csv_rows << " rows)\n";
  }
  return out.str();
}

}  // namespace tumble::app
