// `tumble merge` of bench parts: the plan of the whole bench rebuilt from the job, each part's
// exact rows checked against its shard and its results.csv, then the folder an unsharded bench
// writes, from the same code.
#include <ostream>

#include <nlohmann/json.hpp>

#include "app/analysis/bench_part.hpp"
#include "app/analysis/bench_plan.hpp"
#include "app/analysis/bench_report.hpp"
#include "app/analysis/gnuplot.hpp"
#include "app/analysis/row_part_kinds.hpp"
#include "app/analysis/row_parts.hpp"
#include "app/support/output_folder.hpp"
#include "base/errors.hpp"

namespace tumble::app {
namespace {

using nlohmann::json;

ReferenceCheck reference_check(const json& check, const std::string& source) {
  ReferenceCheck out;
  out.runs = check.at("runs").get<std::string>();
  out.orientation = exact_number_value(check.at("orientation"), source, "check.orientation");
  out.omega = exact_number_value(check.at("omega"), source, "check.omega");
  out.momentum = exact_number_value(check.at("momentum"), source, "check.momentum");
  return out;
}

/// Puts the rows of `part` into `outcome` (the whole bench's plan), after checking that they are
/// its shard's cases and what its results.csv holds; the references of its scenes too.
void read_bench_part(const NamedManifest& part, BenchOutcome& outcome, std::vector<bool>& known) {
  const PartManifest& m = part.manifest;
  const std::string source = (part.part / kPartManifestFile).string();
  const json& payload = m.payload;
  const std::vector<std::size_t> items = index_list(payload.at("cases"), source, "payload.cases");
  if (items != shard_items(m.total, m.shard)) {
    throw InputError(part.part.string() + ": its rows are not the cases of shard " +
                     m.shard.text() + " (" + std::to_string(items.size()) + " listed, " +
                     std::to_string(shard_size(m.total, m.shard, ShardSplit::kStrided)) +
                     " expected)");
  }
  const json& results = payload.at("results");
  if (!results.is_array() || results.size() != items.size()) {
    throw InputError(source + ": field 'payload.results': expected one result per case");
  }
  // The part's own outcome, to write its rows as the bench does and compare with its CSV.
  BenchOutcome piece;
  piece.scenes = std::move(outcome.scenes);
  for (std::size_t k = 0; k < items.size(); ++k) {
    piece.cases.push_back(outcome.cases[items[k]]);
    piece.results.push_back(case_result_from_json(results[k], source));
  }
  try {
    check_part_csv(part.part, "results.csv", results_csv(piece));
  } catch (...) {
    outcome.scenes = std::move(piece.scenes);
    throw;
  }
  outcome.scenes = std::move(piece.scenes);
  for (std::size_t k = 0; k < items.size(); ++k) outcome.results[items[k]] = piece.results[k];
  for (const json& scene : payload.at("scenes")) {
    const auto s = scene.at("scene").get<std::size_t>();
    if (s >= outcome.scenes.size()) {
      throw InputError(source + ": field 'payload.scenes': scene " + std::to_string(s) +
                       " is not one of the job's");
    }
    if (known[s]) continue;
    const json& reference = scene.at("reference");
    outcome.scenes[s].reference.description = reference.at("description").get<std::string>();
    if (!reference.at("check").is_null()) {
      outcome.scenes[s].reference.check = reference_check(reference.at("check"), source);
    }
    known[s] = true;
  }
  const json& workers = payload.at("workers");
  outcome.shards.push_back({workers.at("workers").get<std::size_t>(),
                            workers.at("cores_used").get<std::vector<int>>(),
                            workers.at("cores_available").get<std::size_t>()});
}

/// The whole bench of the parts' job, planned again from its manifest (the scenes checked
/// unchanged), with its results still empty; `gnuplot` checks first that the plots can be drawn.
BenchOutcome planned_bench(const NamedManifest& first_part, bool gnuplot) {
  const PartManifest& first = first_part.manifest;
  BenchOptions options = bench_job_options(first.job);
  BenchOutcome outcome;
  outcome.repeat =
      static_cast<int>(parse_whole_number(options.repeat.value_or("3"), "--repeat", 1));
  if (gnuplot && !gnuplot_available()) {
    throw InputError("gnuplot is not installed (needed for the plots)");
  }
  plan_bench(options, outcome.scenes, outcome.cases);
  if (outcome.cases.size() != first.total) {
    throw InputError(first_part.part.string() + ": the job has " +
                     std::to_string(outcome.cases.size()) + " cases, the part's manifest " +
                     std::to_string(first.total));
  }
  outcome.results.resize(first.total);
  return outcome;
}

/// Reads every part into `outcome` (planned_bench's).
void read_bench_parts(const std::vector<NamedManifest>& parts, BenchOutcome& outcome) {
  std::vector<bool> known(outcome.scenes.size(), false);
  for (const NamedManifest& part : parts) {
    try {
      read_bench_part(part, outcome, known);
    } catch (const json::exception& error) {
      throw InputError((part.part / kPartManifestFile).string() +
                       ": field 'payload': " + error.what());
    }
  }
}

}  // namespace

void check_bench_part(const NamedManifest& part) {
  BenchOutcome outcome = planned_bench(part, false);
  read_bench_parts({part}, outcome);
}

void merge_bench_parts(const std::vector<NamedManifest>& parts, const std::filesystem::path& output,
                       std::ostream& out) {
  BenchOutcome outcome = planned_bench(parts.front(), true);
  read_bench_parts(parts, outcome);
  const std::filesystem::path tmp = start_output_folder(output, kBenchOutput);
  try {
    write_bench_folder(outcome, tmp, output);
    finish_output_folder(tmp, output);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove_all(tmp, ignored);
    throw;
  }
  out << "tumble merge: " << parts.size() << " bench parts, " << outcome.cases.size()
      << " runs; wrote " << (output / "report.md").string() << "\n";
}

}  // namespace tumble::app
