// `tumble stability`: every case x integrator x dt, classified from the signed change of the
// invariants, written as a CSV, a markdown report and a heat map.
//
// Design: this file holds the options and the command's flow (cases, the sweep, the output
// folder, the summary); a run is app/analysis/stability_runner.hpp, the outputs are
// app/analysis/stability_report.hpp.
#include "app/commands/stability_command.hpp"

#include <algorithm>
#include <cstddef>
#include <ostream>

#include <CLI/CLI.hpp>

#include <nlohmann/json.hpp>

#include "app/analysis/gnuplot.hpp"
#include "app/analysis/stability_plot.hpp"
#include "app/analysis/stability_report.hpp"
#include "app/analysis/stability_runner.hpp"
#include "app/analysis/stability_suite.hpp"
#include "app/commands/exit_status.hpp"
#include "app/farm/shard.hpp"
#include "app/scene/option_lists.hpp"
#include "app/support/file_write.hpp"
#include "app/support/interrupt_guard.hpp"
#include "app/support/output_folder.hpp"
#include "base/errors.hpp"
#include "engine/dynamics/integrators.hpp"
#include "row_parts.hpp"
#include "stability_part.hpp"
#include "stability_plan.hpp"

namespace tumble::app {
namespace {

using tumble::InputError;
namespace fs = std::filesystem;

int list_suites(std::ostream& out) {
  for (const SuiteListing& suite : stability_suite_listing()) {
    out << suite.name << "  " << suite.description << "\n";
  }
  return 0;
}

/// Runs every case under every integrator at each of its dts, in the order the outputs read
/// them (stability_report.hpp), with one progress line per case on `err`; with a shard, only
/// the runs of that shard (every N-th of the sweep), a case's reference only when one of its
/// runs is the shard's. Stops early, with the runs so far, when `guard` caught a signal.
std::vector<StabilityRun> run_sweep(const std::vector<StabilityCase>& cases,
                                    const std::vector<engine::IntegratorInfo>& integrators,
                                    const std::optional<Shard>& shard, const InterruptGuard& guard,
                                    std::ostream& err) {
  const std::size_t total = stability_run_count(cases, integrators.size());
  const auto mine = [&](std::size_t run) {
    return !shard || in_shard(run, total, *shard, ShardSplit::kStrided);
  };
  std::vector<StabilityRun> runs;
  std::size_t first = 0;  // the sweep's number of the case's first run
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const StabilityCase& c = cases[k];
    const std::size_t count = integrators.size() * c.dts.size();
    std::size_t taken = 0;
    for (std::size_t i = first; i < first + count; ++i) taken += mine(i);
    err << "tumble stability: [" << k + 1 << "/" << cases.size() << "] " << c.name << ": " << taken
        << " runs\n"
        << std::flush;
    if (guard.interrupted()) return runs;
    if (taken == 0) {
      first += count;
      continue;
    }
    const StabilityReference reference = stability_reference(c);
    for (const engine::IntegratorInfo& info : integrators) {
      for (const double dt : c.dts) {
        if (!mine(first++)) continue;
        if (guard.interrupted()) return runs;
        StabilityRun run =
            run_stability_case(c, info, dt, reference, [&guard] { return guard.interrupted(); });
        if (run.stopped) return runs;  // within the run: it is left out, as are the rest
        runs.push_back(std::move(run));
      }
    }
  }
  return runs;
}

/// The counts of each outcome, and where the outputs went.
void print_summary(const std::vector<StabilityRun>& runs, std::size_t case_count,
                   const fs::path& output, std::ostream& out) {
  std::size_t counts[kStabilityOutcomeCount] = {};
  for (const StabilityRun& r : runs) ++counts[static_cast<int>(r.outcome)];
  out << "tumble stability: " << runs.size() << " runs over " << case_count << " cases: ";
  for (int o = 0; o < kStabilityOutcomeCount; ++o) {
    out << (o ? ", " : "") << counts[o] << " " << outcome_name(static_cast<StabilityOutcome>(o));
  }
  out << "\n  wrote " << (output / "stability.csv").string() << ", stability.md, stability.png, "
      << "stability.svg\n";
}

/// Removes the temporary folder of an interrupted run.
int interrupted_run(const fs::path& temporary) {
  std::error_code ignored;
  fs::remove_all(temporary, ignored);
  return kExitInterrupted;
}

int stability(const StabilityOptions& options, const InterruptGuard& guard, std::ostream& out,
              std::ostream& err) {
  // Options, cases and the output folder are checked before any run.
  std::optional<Shard> shard;
  if (options.shard) shard = parse_shard(*options.shard);
  if (!options.output) {
    throw InputError(shard ? "--shard: -o DIR is required (the folder of the part)"
                           : "-o DIR is required (or --list-suites)");
  }
  const std::vector<engine::IntegratorInfo> integrators =
      parse_stability_integrators(options.integrators);
  std::string suite;
  const std::vector<StabilityCase> cases = gather_stability_cases(options, suite);
  // A part has no heat map: only the merge needs gnuplot.
  if (!shard && !gnuplot_available()) {
    throw InputError("gnuplot is not installed (needed for the heat map)");
  }
  const std::size_t total = stability_run_count(cases, integrators.size());
  const nlohmann::json job = shard ? stability_job(options) : nlohmann::json();
  const fs::path output = *options.output;
  const fs::path temporary =
      start_output_folder(output, shard ? stability_part_kind() : kStabilityOutput);
  try {
    const std::vector<StabilityRun> runs = run_sweep(cases, integrators, shard, guard, err);
    if (guard.interrupted()) return interrupted_run(temporary);

    // The outputs, then the folder into place.
    if (shard) {
      write_stability_part(suite, cases, runs, shard_items(total, *shard), job, *shard, total,
                           temporary, output);
    } else {
      write_stability_folder(suite, cases, integrators, runs, temporary, output);
    }
    if (guard.interrupted()) return interrupted_run(temporary);
    finish_output_folder(temporary, output);
    if (shard) {
      out << "tumble stability: shard " << shard->text() << ": " << runs.size() << " of " << total
          << " runs; wrote " << output.string() << " (a part for tumble merge)\n";
    } else {
      print_summary(runs, cases.size(), output, out);
    }
  } catch (...) {
    std::error_code ignored;
    fs::remove_all(temporary, ignored);
    throw;
  }
  return 0;
}

}  // namespace

CLI::App& add_stability_command(CLI::App& cli, StabilityOptions& options) {
  CLI::App& command =
      *cli.add_subcommand("stability",
                          "Stiff and extreme cases over every integrator and a dt sweep: CSV, "
                          "markdown matrices and a heat map");
  command.add_option_function<std::string>(
      "--suite", [&](const std::string& value) { options.suite = value; },
      "Built-in suite (default standard; see --list-suites)");
  command.add_option_function<std::string>(
      "--integrators", [&](const std::string& value) { options.integrators = value; },
      "Comma-separated integrators (default: all)");
  command.add_option_function<std::string>(
      "--dts", [&](const std::string& value) { options.dts = value; },
      "Comma-separated time steps in s for the SCENE cases (default: the scene's dt x 1, 2, 4, 8)");
  command.add_option_function<std::string>(
      "--cases", [&](const std::string& value) { options.cases = value; },
      "Comma-separated built-in cases of the suite (default: all)");
  command.add_option_function<std::vector<std::string>>(
      "SCENE",
      [&](const std::vector<std::string>& values) {
        for (const std::string& value : values) options.scenes.emplace_back(value);
      },
      "Scene files added as cases (alone: only they run, unless --suite or --cases is given)");
  command.add_option_function<std::string>(
      "-o,--output", [&](const std::string& value) { options.output = value; },
      "Output folder DIR (written atomically: .DIR.tmp-PID renamed at the end); with --shard, "
      "the folder of the part");
  command.add_option_function<std::string>(
      "--shard", [&](const std::string& value) { options.shard = value; },
      "I/N: make only the I-th of N shards of the runs (I from 0; every N-th run of the sweep) "
      "and write -o DIR as a part: its rows and part.json, for tumble merge");
  command.add_flag("--list-suites", options.list_suites, "List the built-in suites, then exit");
  return command;
}

int run_stability(const StabilityOptions& options, std::ostream& out, std::ostream& err) {
  const InterruptGuard guard;
  const std::string output = options.output ? options.output->string() : "";
  const auto interrupted = [&] {
    guard.report(err, "stability", output);
    return kExitInterrupted;
  };
  return run_guarded(
      "stability", err,
      [&] {
        if (options.list_suites) return list_suites(out);
        const int status = stability(options, guard, out, err);
        return status == kExitInterrupted ? interrupted() : status;
      },
      [&] { return guard.interrupted() ? interrupted() : -1; });
}

}  // namespace tumble::app
