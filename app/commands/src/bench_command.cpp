// `tumble bench`: options, validation, the output directory and the run of every case.
#include "app/commands/bench_command.hpp"

#include <ostream>

#include <CLI/CLI.hpp>

#include "app/analysis/bench_job.hpp"
#include "app/support/exit_status.hpp"
#include "app/support/interrupt_guard.hpp"

namespace tumble::app {

CLI::App& add_bench_command(CLI::App& cli, BenchOptions& options) {
  CLI::App& bench = *cli.add_subcommand(
      "bench", "Error against run time for each integrator: results.csv, plots, report.md");
  bench.add_option_function<std::vector<std::string>>(
      "SCENE",
      [&](const std::vector<std::string>& values) {
        options.scenes.assign(values.begin(), values.end());
      },
      "Scene files (JSON)");
  bench.add_option_function<std::string>(
      "--integrators", [&](const std::string& v) { options.integrators = v; },
      "Comma-separated integrators (default: all but exact)");
  bench.add_option_function<std::string>(
      "--dts", [&](const std::string& v) { options.dts = v; },
      "Comma-separated steps in s for fixed-step integrators, each dividing the largest "
      "(default: the scene's dt times 4, 2, 1, 1/2, 1/4)");
  bench.add_option_function<std::string>(
      "--tolerances", [&](const std::string& v) { options.tolerances = v; },
      "Comma-separated tolerances for adaptive integrators (default 1e-4,1e-6,...,1e-12)");
  bench.add_option_function<std::string>(
      "--duration", [&](const std::string& v) { options.duration = v; },
      "Simulated time T in s (default: the scene's)");
  bench.add_option_function<std::string>(
      "--repeat", [&](const std::string& v) { options.repeat = v; },
      "Timed runs per case after the measured warm-up run; their median, min and max are kept "
      "(default 3)");
  bench.add_option_function<std::string>(
      "--jobs", [&](const std::string& v) { options.jobs = v; },
      "Cases run in parallel, one pinned core each, capped at the cores (default 1)");
  bench.add_option_function<std::string>(
      "-o,--output", [&](const std::string& v) { options.output = v; },
      "Output directory DIR (written atomically; an existing one must be empty or a previous "
      "bench output); with --shard, the folder of the part");
  bench.add_option_function<std::string>(
      "--shard", [&](const std::string& v) { options.shard = v; },
      "I/N: run only the I-th of N shards of the cases (I from 0; every N-th case) and write "
      "-o DIR as a part: its rows and part.json, for tumble merge");
  return bench;
}

int run_bench(const BenchOptions& options, std::ostream& out, std::ostream& err) {
  const InterruptGuard guard;
  const auto interrupted = [&] {
    guard.report(err, "bench", options.output.string());
    return kExitInterrupted;
  };
  return run_guarded(
      "bench", err,
      [&] {
        const int status = write_bench(
            options, [&] { return guard.interrupted(); }, out, err);
        return status == kExitInterrupted ? interrupted() : status;
      },
      [&] { return guard.interrupted() ? interrupted() : -1; });
}

}  // namespace tumble::app
