// `tumble stability`'s flow: the sweep run case by case, integrator by integrator, dt by dt,
// then the output folder or the part.
#include "app/analysis/stability_job.hpp"

#include <algorithm>
#include <cstddef>
#include <ostream>

#include <nlohmann/json.hpp>

#include "app/analysis/gnuplot.hpp"
#include "app/analysis/row_parts.hpp"
#include "app/analysis/stability_part.hpp"
#include "app/analysis/stability_plan.hpp"
#include "app/analysis/stability_report.hpp"
#include "app/support/exit_status.hpp"
#include "app/support/output_folder.hpp"
#include "base/errors.hpp"

namespace tumble::app {
namespace {

using ::tumble::InputError;
namespace fs = std::filesystem;

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

}  // namespace

int write_stability(const StabilityOptions& options, const std::function<bool()>& interrupted,
                    std::ostream& out, std::ostream& err) {
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
    const std::vector<StabilityRun> runs =
        run_stability_sweep(cases, integrators, shard, interrupted, &err);
    if (interrupted && interrupted()) return interrupted_run(temporary);

    // The outputs, then the folder into place.
    if (shard) {
      write_stability_part(suite, cases, runs, shard_items(total, *shard), job, *shard, total,
                           temporary, output);
    } else {
      write_stability_folder(suite, cases, integrators, runs, temporary, output);
    }
    if (interrupted && interrupted()) return interrupted_run(temporary);
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

std::vector<StabilityRun> run_stability_sweep(
    const std::vector<StabilityCase>& cases, const std::vector<engine::IntegratorInfo>& integrators,
    const std::optional<Shard>& shard, const std::function<bool()>& stop, std::ostream* progress) {
  const auto stopped = [&] { return stop && stop(); };
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
    if (progress) {
      *progress << "tumble stability: [" << k + 1 << "/" << cases.size() << "] " << c.name << ": "
                << taken << " runs\n"
                << std::flush;
    }
    if (stopped()) return runs;
    if (taken == 0) {
      first += count;
      continue;
    }
    const StabilityReference reference = stability_reference(c);
    for (const engine::IntegratorInfo& info : integrators) {
      for (const double dt : c.dts) {
        if (!mine(first++)) continue;
        if (stopped()) return runs;
        StabilityRun run = run_stability_case(c, info, dt, reference, stopped);
        if (run.stopped) return runs;  // within the run: it is left out, as are the rest
        runs.push_back(std::move(run));
      }
    }
  }
  return runs;
}

std::vector<StabilityRun> run_stability_rows(const StabilityOptions& options,
                                             const std::function<bool()>& stop) {
  std::optional<Shard> shard;
  if (options.shard) shard = parse_shard(*options.shard);
  const std::vector<engine::IntegratorInfo> integrators =
      parse_stability_integrators(options.integrators);
  std::string suite;
  const std::vector<StabilityCase> cases = gather_stability_cases(options, suite);
  return run_stability_sweep(cases, integrators, shard, stop);
}

void list_stability_suites(std::ostream& out) {
  for (const SuiteListing& suite : stability_suite_listing()) {
    out << suite.name << "  " << suite.description << "\n";
  }
}

}  // namespace tumble::app
