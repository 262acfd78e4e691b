#pragma once
/// @file `tumble stability`: runs stiff and extreme cases (engine/PHYSICS.md §7) over every
/// integrator and a dt sweep, classifies each run (stable, drifting, damped, blew up) and writes
/// a CSV, a markdown report with one matrix per case and a heat map.

#include <iosfwd>

#include "app/analysis/stability_options.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace tumble::app {

/// Adds the `stability` subcommand and its options to `cli`, filling `options` when parsed.
CLI::App& add_stability_command(CLI::App& cli, StabilityOptions& options);

/// Runs the command. Returns 0, or kExitInputError (1) with one line on `err`.
int run_stability(const StabilityOptions& options, std::ostream& out, std::ostream& err);

}  // namespace tumble::app
