#pragma once
/// @file `tumble simulate`: runs a scene without rendering, writes the trajectory as CSV and
/// summarises how well the invariants held.

#include <iosfwd>

#include "app/analysis/simulation_run.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace tumble::app {

/// Adds the `simulate` subcommand and its options to `cli`, filling `options` when parsed.
CLI::App& add_simulate_command(CLI::App& cli, SimulateOptions& options);

/// Runs the command. Returns 0, kExitInputError (message on `err`) or kExitBlowUp (one line on
/// `err`; the summary still goes to `out` and the CSV holds every row up to the last good step).
int run_simulate(const SimulateOptions& options, std::ostream& out, std::ostream& err);

}  // namespace tumble::app
