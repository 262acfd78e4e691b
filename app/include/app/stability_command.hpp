#pragma once
/// @file `tumble stability`: runs stiff and extreme cases (engine/PHYSICS.md §7) over every
/// integrator and a dt sweep, classifies each run (stable, drifting, damped, blew up) and writes
/// a CSV, a markdown report with one matrix per case and a heat map.

#include <cstddef>
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace CLI {
class App;
}  // namespace CLI

namespace tumble::app {

/// What `tumble stability` was asked to do.
struct StabilityOptions {
  std::optional<std::string> suite;         ///< default "standard" (none when only scenes are given)
  std::optional<std::string> integrators;   ///< comma-separated names; default all
  std::optional<std::string> dts;           ///< comma-separated seconds, for scene cases
  std::optional<std::string> cases;         ///< comma-separated built-in case names
  std::vector<std::filesystem::path> scenes;
  std::optional<std::filesystem::path> output;
  bool list_suites = false;
};

/// Adds the `stability` subcommand and its options to `cli`, filling `options` when parsed.
CLI::App& add_stability_command(CLI::App& cli, StabilityOptions& options);

/// The relative drift above which a run is no longer `stable` (energy and |L|, over the run).
inline constexpr double kStabilityDriftThreshold = 1e-3;

/// The outcome of one run.
enum class StabilityOutcome { kStable, kDrifting, kDamped, kBlewUp, kUnchecked, kSkipped };

/// The outcome as written in the outputs: "stable", "drifting", "damped", "blew up",
/// "unchecked" (no invariant applies), "skipped".
const char* outcome_name(StabilityOutcome outcome);

/// How the invariants (energy of conservative bodies, |L| of torque-free bodies, each summed
/// over the bodies) changed over one run, relative to their initial values (absolute when
/// those are zero). Signed: positive is growth, negative is loss.
struct InvariantChanges {
  bool energy_applies = false;
  bool momentum_applies = false;
  double energy_final = 0.0;     ///< (E_end - E0) / |E0|
  double energy_max_gain = 0.0;  ///< max over the run of (E - E0) / |E0|, >= 0
  double energy_max_loss = 0.0;  ///< max over the run of (E0 - E) / |E0|, >= 0
  double energy_late_min = 0.0;  ///< min of (E - E0) / |E0| over the last quarter of the steps
  double energy_late_max = 0.0;  ///< max of (E - E0) / |E0| over the last quarter of the steps
  double momentum_final = 0.0;
  double momentum_max_gain = 0.0;
  double momentum_max_loss = 0.0;
  double momentum_late_min = 0.0;
  double momentum_late_max = 0.0;
};

/// The classification rules (documented in the report):
///  1. `blew up` when the simulation reported a blow-up;
///  2. `unchecked` when neither energy nor |L| is an invariant of the case;
///  3. `stable` when every applicable invariant stayed within `threshold` of its initial value
///     over the whole run (max gain and max loss both <= threshold);
///  4. `damped` when an invariant stays below its initial value by more than `threshold` over
///     the whole last quarter of the run (late max < -threshold), swinging there by less than
///     half its loss (late max - late min < |late max| / 2: a wide bounded oscillation below
///     X0, as Verlet's on a spring, is not damping), and no invariant ever gained more than
///     `threshold`;
///  5. `drifting` otherwise (bounded, but a gain beyond `threshold`, or swings beyond it).
StabilityOutcome classify(bool blew_up, const InvariantChanges& changes, double threshold);

/// Runs the command. Returns 0, or kExitInputError (1) with one line on `err`.
int run_stability(const StabilityOptions& options, std::ostream& out, std::ostream& err);

}  // namespace tumble::app
