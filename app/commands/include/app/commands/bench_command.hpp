#pragma once
/// @file `tumble bench`: error against run time for every integrator over a sweep of step sizes
/// (tolerances for adaptive integrators), with work-precision diagrams and a report.
///
/// Writes DIR/results.csv (one row per run), DIR/<scene>_<measure>.{png,svg} and DIR/report.md.
/// DIR is built as .DIR.tmp-PID and renamed into place at the end; an existing DIR must be
/// empty or a previous bench output (it holds report.md starting with "# tumble bench"), which
/// is replaced. Blown-up runs are results, not failures: the exit status is 0 with them.

#include <iosfwd>

#include "app/analysis/bench_options.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace tumble::app {

/// Adds the `bench` subcommand and its options to `cli`, filling `options` when parsed.
CLI::App& add_bench_command(CLI::App& cli, BenchOptions& options);

/// Runs the command. Returns 0, or 1 with one line on `err` (bad scene or option, output
/// directory not writable or not replaceable, gnuplot missing or failing).
int run_bench(const BenchOptions& options, std::ostream& out, std::ostream& err);

}  // namespace tumble::app
