// `tumble bench`: options, validation, the output directory and the run of every case.
#include "app/commands/bench_command.hpp"

#include <algorithm>
#include <optional>
#include <ostream>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "app/analysis/bench_report.hpp"
#include "app/analysis/bench_runner.hpp"
#include "app/analysis/gnuplot.hpp"
#include "app/commands/exit_status.hpp"
#include "app/farm/shard.hpp"
#include "app/support/interrupt_guard.hpp"
#include "app/support/output_folder.hpp"
#include "app/support/printf_number.hpp"
#include "app/support/progress_bar.hpp"
#include "base/errors.hpp"
#include "bench_part.hpp"
#include "bench_plan.hpp"
#include "row_parts.hpp"

namespace tumble::app {
namespace {

using tumble::InputError;

std::string case_line(const BenchScene& scene, const BenchCase& c, const CaseResult& r) {
  std::string line = scene.label + " " + c.integrator + " " +
                     (c.tolerance ? "tol " + printf_number(*c.tolerance, "%.3g")
                                  : "dt " + printf_number(c.dt, "%.4g")) +
                     ": " + printf_number(r.median_seconds, "%.3g") + " s, ";
  if (r.blow_up_time) return line + "blew up at t = " + printf_number(*r.blow_up_time) + " s";
  return line + "orientation error " + printf_number(r.errors.orientation_final, "%.2e") + " rad";
}

/// Thrown out of a run that caught SIGINT or SIGTERM, to remove its outputs on the way out.
struct Interrupted {};

/// The references of the scenes the cases use, then the cases, one line (or a bar on a
/// terminal) each. Throws Interrupted.
void run_all(BenchOutcome& outcome, std::size_t jobs, const InterruptGuard& guard,
             std::ostream& err) {
  std::vector<bool> used(outcome.scenes.size(), false);
  for (const BenchCase& c : outcome.cases) used[c.scene] = true;
  for (std::size_t s = 0; s < outcome.scenes.size(); ++s) {
    if (!used[s]) continue;
    BenchScene& scene = outcome.scenes[s];
    try {
      scene.reference = make_reference(scene.bodies, scene.initial, scene.grid);
    } catch (const InputError& error) {
      throw InputError(scene.file.string() + ": " + error.what());
    }
    if (guard.interrupted()) throw Interrupted{};
  }
  const std::vector<int> cores = available_cores();
  outcome.cores_available = cores.size();
  outcome.workers = std::clamp<std::size_t>(jobs, 1, cores.size());
  outcome.cores_used.assign(cores.begin(), cores.begin() + static_cast<long>(outcome.workers));
  const bool tty = ProgressBar::on_terminal(err);
  ProgressBar bar(err, outcome.cases.size(), "runs", tty);
  const std::size_t total = outcome.cases.size();
  outcome.results = run_cases(
      outcome.scenes, outcome.cases, outcome.repeat, outcome.workers,
      [&](std::size_t i, const CaseResult& r, std::size_t finished) {
        if (tty) {
          bar.update(finished);
        } else {
          err << "tumble bench: [" << finished << "/" << total << "] "
              << case_line(outcome.scenes[outcome.cases[i].scene], outcome.cases[i], r) << "\n";
        }
      },
      [&] { return guard.interrupted(); });
  bar.clear();
  if (guard.interrupted()) throw Interrupted{};
}

int bench(const BenchOptions& options, const InterruptGuard& guard, std::ostream& out,
          std::ostream& err) {
  // Everything the user typed is checked before any output is created, the cheap checks
  // before the scenes' meshes are read.
  BenchOutcome outcome;
  outcome.repeat =
      static_cast<int>(parse_whole_number(options.repeat.value_or("3"), "--repeat", 1));
  const auto jobs =
      static_cast<std::size_t>(parse_whole_number(options.jobs.value_or("1"), "--jobs", 1));
  std::optional<Shard> shard;
  if (options.shard) shard = parse_shard(*options.shard);
  if (options.output.empty()) {
    throw InputError(shard ? "--shard: -o DIR is required (the folder of the part)"
                           : "-o DIR is required");
  }
  // A part has no plots: only the merge needs gnuplot.
  if (!shard && !gnuplot_available()) {
    throw InputError("gnuplot is not installed (needed for the plots)");
  }
  plan_bench(options, outcome.scenes, outcome.cases);
  const std::size_t total = outcome.cases.size();
  std::vector<std::size_t> items;
  nlohmann::json job;
  if (shard) {
    job = bench_job(options);
    items = shard_items(total, *shard);
    std::vector<BenchCase> mine;
    for (const std::size_t i : items) mine.push_back(outcome.cases[i]);
    outcome.cases = std::move(mine);
  }
  const std::filesystem::path tmp =
      start_output_folder(options.output, shard ? bench_part_kind() : kBenchOutput);
  try {
    run_all(outcome, jobs, guard, err);
    // Outputs, then the directory into place; a failed write names the file by its final name.
    if (shard) {
      write_bench_part(outcome, items, job, *shard, total, tmp, options.output);
    } else {
      write_bench_folder(outcome, tmp, options.output);
    }
    if (guard.interrupted()) throw Interrupted{};
    finish_output_folder(tmp, options.output);
  } catch (const Interrupted&) {
    std::error_code ignored;
    std::filesystem::remove_all(tmp, ignored);
    return kExitInterrupted;
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove_all(tmp, ignored);
    throw;
  }
  out << "tumble bench: " << (shard ? "shard " + shard->text() + ": " : "") << outcome.cases.size()
      << (shard ? " of " + std::to_string(total) : "") << " runs on " << outcome.workers
      << " core(s); wrote "
      << (shard ? options.output.string() + " (a part for tumble merge)"
                : (options.output / "report.md").string())
      << "\n";
  return 0;
}

}  // namespace

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
        const int status = bench(options, guard, out, err);
        return status == kExitInterrupted ? interrupted() : status;
      },
      [&] { return guard.interrupted() ? interrupted() : -1; });
}

}  // namespace tumble::app
