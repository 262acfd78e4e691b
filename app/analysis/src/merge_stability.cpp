// `tumble merge` of stability parts: the sweep's cases rebuilt from the job, each part's exact
// runs checked against its shard and its stability.csv, then the folder an unsharded sweep
// writes, from the same code.
#include <ostream>

#include <nlohmann/json.hpp>

#include "app/analysis/gnuplot.hpp"
#include "app/analysis/row_part_kinds.hpp"
#include "app/analysis/row_parts.hpp"
#include "app/analysis/stability_part.hpp"
#include "app/analysis/stability_plan.hpp"
#include "app/analysis/stability_report.hpp"
#include "app/support/output_folder.hpp"
#include "base/errors.hpp"

namespace tumble::app {
namespace {

using nlohmann::json;

/// The sweep's runs in order as (case, integrator, dt) keys.
struct RunKey {
  std::string case_name;
  std::string integrator;
  double dt = 0.0;
};

std::vector<RunKey> run_keys(const std::vector<StabilityCase>& cases,
                             const std::vector<engine::IntegratorInfo>& integrators) {
  std::vector<RunKey> keys;
  for (const StabilityCase& c : cases) {
    for (const engine::IntegratorInfo& info : integrators) {
      for (const double dt : c.dts) keys.push_back({c.name, info.name, dt});
    }
  }
  return keys;
}

/// Puts the runs of `part` at their places in `runs`, after checking that they are its shard's
/// runs of the sweep and what its stability.csv holds.
void read_stability_part(const NamedManifest& part, const std::string& suite,
                         const std::vector<StabilityCase>& cases, const std::vector<RunKey>& keys,
                         std::vector<StabilityRun>& runs) {
  const PartManifest& m = part.manifest;
  const std::string source = (part.part / kPartManifestFile).string();
  const std::vector<std::size_t> items = index_list(m.payload.at("runs"), source, "payload.runs");
  if (items != shard_items(m.total, m.shard)) {
    throw InputError(part.part.string() + ": its rows are not the runs of shard " + m.shard.text() +
                     " (" + std::to_string(items.size()) + " listed, " +
                     std::to_string(shard_size(m.total, m.shard, ShardSplit::kStrided)) +
                     " expected)");
  }
  const json& results = m.payload.at("results");
  if (!results.is_array() || results.size() != items.size()) {
    throw InputError(source + ": field 'payload.results': expected one result per run");
  }
  std::vector<StabilityRun> mine;
  for (std::size_t k = 0; k < items.size(); ++k) {
    StabilityRun run = stability_run_from_json(results[k], source);
    const RunKey& key = keys[items[k]];
    if (run.case_name != key.case_name || run.integrator != key.integrator || run.dt != key.dt) {
      throw InputError(source + ": run " + std::to_string(items[k]) + " is " + run.case_name + " " +
                       run.integrator + ", not the sweep's " + key.case_name + " " +
                       key.integrator);
    }
    mine.push_back(std::move(run));
  }
  check_part_csv(part.part, "stability.csv", stability_csv(suite, cases, mine));
  for (std::size_t k = 0; k < items.size(); ++k) runs[items[k]] = std::move(mine[k]);
}

/// The sweep of the parts' job, planned again from its manifest (the scenes checked
/// unchanged), and its runs read from `parts`; `gnuplot` checks first that the heat map can be
/// drawn.
struct ReadSweep {
  std::string suite;
  std::vector<StabilityCase> cases;
  std::vector<engine::IntegratorInfo> integrators;
  std::vector<StabilityRun> runs;
};
ReadSweep read_stability_parts(const std::vector<NamedManifest>& parts, bool gnuplot) {
  const PartManifest& first = parts.front().manifest;
  const StabilityOptions options = stability_job_options(first.job);
  ReadSweep sweep;
  sweep.integrators = parse_stability_integrators(options.integrators);
  sweep.cases = gather_stability_cases(options, sweep.suite);
  if (gnuplot && !gnuplot_available()) {
    throw InputError("gnuplot is not installed (needed for the heat map)");
  }
  const std::vector<RunKey> keys = run_keys(sweep.cases, sweep.integrators);
  if (keys.size() != first.total) {
    throw InputError(parts.front().part.string() + ": the job has " + std::to_string(keys.size()) +
                     " runs, the part's manifest " + std::to_string(first.total));
  }
  sweep.runs.resize(keys.size());
  for (const NamedManifest& part : parts) {
    try {
      read_stability_part(part, sweep.suite, sweep.cases, keys, sweep.runs);
    } catch (const json::exception& error) {
      throw InputError((part.part / kPartManifestFile).string() +
                       ": field 'payload': " + error.what());
    }
  }
  return sweep;
}

}  // namespace

void check_stability_part(const NamedManifest& part) {
  read_stability_parts({part}, false);
}

void merge_stability_parts(const std::vector<NamedManifest>& parts,
                           const std::filesystem::path& output, std::ostream& out) {
  const ReadSweep sweep = read_stability_parts(parts, true);
  const std::string& suite = sweep.suite;
  const std::vector<StabilityCase>& cases = sweep.cases;
  const std::vector<engine::IntegratorInfo>& integrators = sweep.integrators;
  const std::vector<StabilityRun>& runs = sweep.runs;
  const std::filesystem::path tmp = start_output_folder(output, kStabilityOutput);
  try {
    write_stability_folder(suite, cases, integrators, runs, tmp, output);
    finish_output_folder(tmp, output);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove_all(tmp, ignored);
    throw;
  }
  out << "tumble merge: " << parts.size() << " stability parts, " << runs.size() << " runs; wrote "
      << (output / "stability.csv").string() << ", stability.md, stability.png, stability.svg\n";
}

}  // namespace tumble::app
