#pragma once
/// @file `tumble simulate`: runs a scene without rendering, writes the trajectory as CSV and
/// summarises how well the invariants held.

#include <cstddef>
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/commands/exit_status.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace tumble::app {

/// What `tumble simulate` was asked to do. Options given here override the scene.
struct SimulateOptions {
  std::filesystem::path scene;
  std::optional<std::string> integrator;
  std::optional<double> dt;
  std::optional<double> duration;
  std::optional<double> tolerance;           ///< relative tolerance of adaptive integrators
  std::optional<double> absolute_tolerance;  ///< their absolute tolerance
  std::optional<double> blowup_factor;
  std::optional<std::filesystem::path> csv;
  long long every = 1;  ///< write every Nth step (the first and the last always)
  bool json = false;
  bool list_integrators = false;
  bool allow_long = false;  ///< run beyond kMaxStepsWithoutAllowLong steps or kMaxCsvBytes of CSV
};

/// Runs longer than this many steps, or CSVs estimated larger than this many bytes, are refused
/// unless --allow-long is given (a mistyped --dt 1e-9 is 2e10 steps and 8 TB of CSV).
inline constexpr double kMaxStepsWithoutAllowLong = 1e9;
inline constexpr double kMaxCsvBytes = 10e9;
/// The estimated size of one CSV row (19 fields of up to 24 characters, a short body name).
inline constexpr double kCsvRowBytes = 400.0;

/// Adds the `simulate` subcommand and its options to `cli`, filling `options` when parsed.
CLI::App& add_simulate_command(CLI::App& cli, SimulateOptions& options);

/// How one body's invariants fared over a run.
struct BodySummary {
  std::string name;
  bool energy_conserved = true;    ///< energy is an invariant of this body's equations
  bool momentum_conserved = true;  ///< |L| is an invariant (torque-free about the centre)
  double energy_drift_max = 0.0;   ///< max |E - E0| / |E0| (absolute when E0 = 0)
  double energy_drift_final = 0.0;
  double momentum_drift_max = 0.0;  ///< max | |L| - |L0| | / |L0| (absolute when L0 = 0)
  double momentum_drift_final = 0.0;
  std::optional<double> orientation_error;  ///< rad, against the exact solution (§4, §4b)
};

/// What a run did.
struct RunSummary {
  std::string scene;           ///< the scene's name
  std::filesystem::path file;  ///< the scene file
  std::string integrator;
  double dt = 0.0;
  double duration = 0.0;
  std::size_t steps = 0;        ///< steps completed
  std::size_t total_steps = 0;  ///< steps the duration needs
  double time = 0.0;            ///< simulated time reached, s
  double wall_seconds = 0.0;    ///< the stepping loop only
  std::optional<std::filesystem::path> csv;
  std::size_t csv_rows = 0;
  std::vector<BodySummary> bodies;
  std::optional<std::string> blow_up;  ///< the one-line message, when the run blew up
};

/// The summary as one JSON object.
nlohmann::json summary_to_json(const RunSummary& summary);

/// The summary as readable text.
std::string format_summary(const RunSummary& summary);

/// Runs the command. Returns 0, kExitInputError (message on `err`) or kExitBlowUp (one line on
/// `err`; the summary still goes to `out` and the CSV holds every row up to the last good step).
int run_simulate(const SimulateOptions& options, std::ostream& out, std::ostream& err);

}  // namespace tumble::app
