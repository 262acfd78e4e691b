#pragma once
/// @file `tumble stability`: runs stiff and extreme cases (engine/PHYSICS.md §7) over every
/// integrator and a dt sweep, classifies each run (stable, drifting, damped, blew up) and writes
/// a CSV, a markdown report with one matrix per case and a heat map.

#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "app/analysis/stability_classes.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace tumble::app {

/// What `tumble stability` was asked to do.
struct StabilityOptions {
  std::optional<std::string> suite;        ///< default "standard" (none when only scenes are given)
  std::optional<std::string> integrators;  ///< comma-separated names; default all
  std::optional<std::string> dts;          ///< comma-separated seconds, for scene cases
  std::optional<std::string> cases;        ///< comma-separated built-in case names
  std::vector<std::filesystem::path> scenes;
  std::optional<std::filesystem::path> output;
  std::optional<std::string> shard;  ///< "I/N": only that shard's runs, written as a part
  bool list_suites = false;
};

/// Adds the `stability` subcommand and its options to `cli`, filling `options` when parsed.
CLI::App& add_stability_command(CLI::App& cli, StabilityOptions& options);

/// Runs the command. Returns 0, or kExitInputError (1) with one line on `err`.
int run_stability(const StabilityOptions& options, std::ostream& out, std::ostream& err);

}  // namespace tumble::app
