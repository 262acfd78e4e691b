#pragma once
/// @file `tumble bench`: error against run time for every integrator over a sweep of step sizes
/// (tolerances for adaptive integrators), with work-precision diagrams and a report.
///
/// Writes DIR/results.csv (one row per run), DIR/<scene>_<measure>.{png,svg} and DIR/report.md.
/// DIR is built as .DIR.tmp-PID and renamed into place at the end; an existing DIR must be
/// empty or a previous bench output (it holds report.md starting with "# tumble bench"), which
/// is replaced. Blown-up runs are results, not failures: the exit status is 0 with them.

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

/// What `tumble bench` was asked to do (lists and numbers as typed; run_bench checks them).
struct BenchOptions {
  std::vector<std::filesystem::path> scenes;
  std::optional<std::string> integrators;  ///< comma-separated names
  std::optional<std::string> dts;          ///< comma-separated steps, s (fixed-step integrators)
  std::optional<std::string> tolerances;   ///< comma-separated tolerances (adaptive ones)
  std::optional<std::string> duration;     ///< s
  std::optional<std::string> repeat;       ///< timed runs per case (default 3)
  std::optional<std::string> jobs;         ///< worker threads, capped at the cores (default 1)
  std::optional<std::string> shard;        ///< "I/N": only that shard's cases, written as a part
  std::filesystem::path output;
};

/// Default step factors around the scene's dt, and default tolerances of adaptive integrators.
inline constexpr double kDefaultStepFactors[] = {4.0, 2.0, 1.0, 0.5, 0.25};
inline constexpr double kDefaultTolerances[] = {1e-4, 1e-6, 1e-8, 1e-10, 1e-12};

/// Adds the `bench` subcommand and its options to `cli`, filling `options` when parsed.
CLI::App& add_bench_command(CLI::App& cli, BenchOptions& options);

/// Runs the command. Returns 0, or 1 with one line on `err` (bad scene or option, output
/// directory not writable or not replaceable, gnuplot missing or failing).
int run_bench(const BenchOptions& options, std::ostream& out, std::ostream& err);

}  // namespace tumble::app
