// `tumble simulate`: scene in, trajectory CSV and an invariants summary out.
#include "app/commands/simulate_command.hpp"

#include <ostream>

#include <CLI/CLI.hpp>

#include "app/support/exit_status.hpp"
#include "app/support/interrupt_guard.hpp"

namespace tumble::app {

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

int run_simulate(const SimulateOptions& options, std::ostream& out, std::ostream& err) {
  if (options.list_integrators) {
    list_integrators(options.json, out);
    return kExitDone;
  }
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
        const int status = simulate_scene(
            options, [&] { return guard.interrupted(); }, summary, err);
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
