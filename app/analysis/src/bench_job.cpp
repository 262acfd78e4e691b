// `tumble bench`'s flow: settings, plan, the references and cases on pinned workers, the
// output folder or the part.
#include "app/analysis/bench_job.hpp"

#include <algorithm>
#include <ostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "app/analysis/bench_part.hpp"
#include "app/analysis/bench_plan.hpp"
#include "app/analysis/bench_runner.hpp"
#include "app/analysis/gnuplot.hpp"
#include "app/analysis/row_parts.hpp"
#include "app/support/exit_status.hpp"
#include "app/support/output_folder.hpp"
#include "app/support/printf_number.hpp"
#include "app/support/progress_bar.hpp"
#include "base/errors.hpp"

namespace tumble::app {
namespace {

using ::tumble::InputError;

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
void run_all(BenchOutcome& outcome, std::size_t jobs, const std::function<bool()>& stop,
             std::ostream* err) {
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
    if (stop && stop()) throw Interrupted{};
  }
  const std::vector<int> cores = available_cores();
  outcome.cores_available = cores.size();
  outcome.workers = std::clamp<std::size_t>(jobs, 1, cores.size());
  outcome.cores_used.assign(cores.begin(), cores.begin() + static_cast<long>(outcome.workers));
  std::ostringstream silent;
  std::ostream& lines = err ? *err : silent;
  const bool tty = err && ProgressBar::on_terminal(*err);
  ProgressBar bar(lines, outcome.cases.size(), "runs", tty);
  const std::size_t total = outcome.cases.size();
  outcome.results = run_cases(
      outcome.scenes, outcome.cases, outcome.repeat, outcome.workers,
      [&](std::size_t i, const CaseResult& r, std::size_t finished) {
        if (tty) {
          bar.update(finished);
        } else {
          lines << "tumble bench: [" << finished << "/" << total << "] "
                << case_line(outcome.scenes[outcome.cases[i].scene], outcome.cases[i], r) << "\n";
        }
      },
      stop);
  bar.clear();
  if (stop && stop()) throw Interrupted{};
}

}  // namespace

BenchRun bench_settings(const BenchOptions& options) {
  BenchRun run;
  run.outcome.repeat =
      static_cast<int>(parse_whole_number(options.repeat.value_or("3"), "--repeat", 1));
  run.jobs = static_cast<std::size_t>(parse_whole_number(options.jobs.value_or("1"), "--jobs", 1));
  if (options.shard) run.shard = parse_shard(*options.shard);
  return run;
}

void plan_bench_run(const BenchOptions& options, BenchRun& run) {
  plan_bench(options, run.outcome.scenes, run.outcome.cases);
  run.total = run.outcome.cases.size();
  if (!run.shard) return;
  run.items = shard_items(run.total, *run.shard);
  std::vector<BenchCase> mine;
  for (const std::size_t i : run.items) mine.push_back(run.outcome.cases[i]);
  run.outcome.cases = std::move(mine);
}

bool run_bench_cases(BenchRun& run, const std::function<bool()>& stop, std::ostream* progress) {
  try {
    run_all(run.outcome, run.jobs, stop, progress);
  } catch (const Interrupted&) {
    return false;
  }
  return true;
}

std::optional<BenchOutcome> run_bench_rows(const BenchOptions& options,
                                           const std::function<bool()>& stop) {
  BenchRun run = bench_settings(options);
  plan_bench_run(options, run);
  if (!run_bench_cases(run, stop)) return std::nullopt;
  return std::move(run.outcome);
}

int write_bench(const BenchOptions& options, const std::function<bool()>& interrupted,
                std::ostream& out, std::ostream& err) {
  // Everything the user typed is checked before any output is created, the cheap checks
  // before the scenes' meshes are read.
  BenchRun run = bench_settings(options);
  const std::optional<Shard>& shard = run.shard;
  if (options.output.empty()) {
    throw InputError(shard ? "--shard: -o DIR is required (the folder of the part)"
                           : "-o DIR is required");
  }
  // A part has no plots: only the merge needs gnuplot.
  if (!shard && !gnuplot_available()) {
    throw InputError("gnuplot is not installed (needed for the plots)");
  }
  plan_bench_run(options, run);
  const nlohmann::json job = shard ? bench_job(options) : nlohmann::json();
  BenchOutcome& outcome = run.outcome;
  const std::filesystem::path tmp =
      start_output_folder(options.output, shard ? bench_part_kind() : kBenchOutput);
  try {
    if (!run_bench_cases(run, interrupted, &err)) throw Interrupted{};
    // Outputs, then the directory into place; a failed write names the file by its final name.
    if (shard) {
      write_bench_part(outcome, run.items, job, *shard, run.total, tmp, options.output);
    } else {
      write_bench_folder(outcome, tmp, options.output);
    }
    if (interrupted && interrupted()) throw Interrupted{};
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
      << (shard ? " of " + std::to_string(run.total) : "") << " runs on " << outcome.workers
      << " core(s); wrote "
      << (shard ? options.output.string() + " (a part for tumble merge)"
                : (options.output / "report.md").string())
      << "\n";
  return 0;
}

}  // namespace tumble::app
