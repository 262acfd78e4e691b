#pragma once
/// @file `tumble farm slurm|parallel [options] -- COMMAND...`: a tumble command (render,
/// compare, bench, stability, inspect) cut into N shards run by Slurm (an array job, then a
/// merge job) or GNU parallel (over ssh hosts or local slots, then the merge). Prints the
/// script; `--submit` (Slurm) or `--run` (parallel) runs it.

#include <iosfwd>

#include "app/farm/farm_run.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace tumble::app {

/// Adds `farm` with its two subcommands to `cli`, filling `options` when parsed.
CLI::App& add_farm_command(CLI::App& cli, FarmOptions& options);

/// Runs the command: 0, or 1 with one line on `err` (bad option or command, a path the
/// workers cannot reach, sbatch or a job failing). The script goes to `out`; warnings to `err`.
int run_farm(const FarmOptions& options, std::ostream& out, std::ostream& err);

}  // namespace tumble::app
