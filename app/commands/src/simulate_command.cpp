// `tumble simulate`: scene in, trajectory CSV and an invariants summary out.
#include "app/commands/simulate_command.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <sstream>

#include <CLI/CLI.hpp>

#include "app/analysis/simulation_run.hpp"
#include "app/scene/scene.hpp"
#include "app/support/csv_writer.hpp"
#include "app/support/interrupt_guard.hpp"
#include "app/support/printf_number.hpp"
#include "base/errors.hpp"
#include "engine/dynamics/integrators.hpp"
#include "engine/simulation/simulation.hpp"

namespace tumble::app {
namespace {

using tumble::InputError;

int list_integrators(bool as_json, std::ostream& out) {
  const auto& catalog = engine::integrator_catalog();
  if (as_json) {
    out << integrators_to_json().dump(2) << "\n";
    return 0;
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
  return 0;
}

/// Runs the scene, filling `summary` and writing the CSV; returns the exit status
/// (kExitInterrupted, with nothing written, when `guard` caught a signal).
int simulate(const SimulateOptions& options, const InterruptGuard& guard, RunSummary& summary,
             std::ostream& err) {
  // Scene and options: everything is checked before any output is created.
  SimulationRun run(options, load_scene(options.scene));

  // The CSV's temporary file is created now, so an unwritable path fails before the run.
  std::optional<TrajectoryCsv> csv;
  if (options.csv) csv.emplace(*options.csv, scene_inputs(run.scene()));
  const auto record = [&](const engine::Simulation& simulation) {
    if (csv) csv->write_rows(simulation.time(), simulation.bodies(), simulation.states());
  };
  if (!run.run(record, [&] { return guard.interrupted(); })) {
    return kExitInterrupted;  // the CSV's temporary goes with `csv`
  }
  summary = run.summary();
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

}  // namespace

CLI::App& add_simulate_command(CLI::App& cli, SimulateOptions& options) {
  CLI::App& simulate = *cli.add_subcommand(
      "simulate", "Run a scene without rendering: trajectory CSV and an invariants summary");
  simulate.add_option_function<std::string>(
      "SCENE", [&](const std::string& value) { options.scene = value; }, "Scene file (JSON)");
  simulate.add_option_function<std::string>(
      "--integrator", [&](const std::string& value) { options.integrator = value; },
      "Integrator name (overrides the scene; see --list-integrators)");
  simulate.add_option_function<double>(
      "--dt", [&](double value) { options.dt = value; }, "Time step H in seconds");
  simulate.add_option_function<double>(
      "--duration", [&](double value) { options.duration = value; }, "Simulated time T in seconds");
  simulate.add_option_function<double>(
      "--tolerance", [&](double value) { options.tolerance = value; },
      "Relative local error tolerance RTOL of adaptive integrators (default 1e-10)");
  simulate.add_option_function<double>(
      "--absolute-tolerance", [&](double value) { options.absolute_tolerance = value; },
      "Absolute local error tolerance ATOL of adaptive integrators, in each quantity's SI unit "
      "(m, m/s, rad, kg m^2/s; default 0)");
  simulate.add_option_function<std::string>(
      "--csv", [&](const std::string& value) { options.csv = value; },
      "Write the trajectory to FILE (written atomically)");
  simulate.add_option("--every", options.every,
                      "Write every Nth step to the CSV (the first and last always; default 1)");
  simulate.add_flag("--json", options.json, "Print the summary as one JSON object");
  simulate.add_option_function<double>(
      "--blowup-factor", [&](double value) { options.blowup_factor = value; },
      "Energy or |L| growth F that stops the run as a blow-up (default 10)");
  simulate.add_flag("--allow-long", options.allow_long,
                    "Run more than 1e9 steps, or write a CSV of more than 10 GB");
  simulate.add_flag("--list-integrators", options.list_integrators,
                    "List the integrators with their order and properties, then exit");
  return simulate;
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

int run_simulate(const SimulateOptions& options, std::ostream& out, std::ostream& err) {
  if (options.list_integrators) return list_integrators(options.json, out);
  if (options.scene.empty()) {
    err << "tumble simulate: error: a SCENE file is required (or --list-integrators)\n";
    return kExitInputError;
  }
  const InterruptGuard guard;
  const std::string output = options.csv ? options.csv->string() : "";
  const auto interrupted = [&] {
    guard.report(err, "simulate", output);
    return kExitInterrupted;
  };
  return run_guarded(
      "simulate", err,
      [&] {
        RunSummary summary;
        const int status = simulate(options, guard, summary, err);
        if (status == kExitInterrupted) return interrupted();
        if (options.json) {
          out << summary_to_json(summary).dump(2) << "\n";
        } else {
          out << format_summary(summary);
        }
        return status;
      },
      [&] { return guard.interrupted() ? interrupted() : -1; });
}

}  // namespace tumble::app
