#pragma once
/// @file A shard of `tumble bench` (`--shard I/N`): the job its manifest names, and its rows
/// (the cases of the shard) kept exactly in the manifest's payload beside results.csv, so that
/// `tumble merge` rebuilds the outcome of the whole bench bit for bit.

#include <cstddef>
#include <filesystem>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/analysis/bench_options.hpp"
#include "app/analysis/bench_report.hpp"
#include "app/farm/part_manifest.hpp"
#include "app/support/output_folder.hpp"

namespace tumble::app {

/// The bench job: the command, each scene with its and its meshes' digests, and the options
/// that change the output (integrators, dts, tolerances, duration, repeat), never --shard, -o
/// or --jobs.
nlohmann::json bench_job(const BenchOptions& options);

/// The options of `job` (bench_job's), after checking that the scenes and meshes are unchanged.
BenchOptions bench_job_options(const nlohmann::json& job);

/// A case's result as JSON (every double exact) and back; the latter throws InputError naming
/// `source`.
nlohmann::json case_result_json(const CaseResult& result);
CaseResult case_result_from_json(const nlohmann::json& json, const std::string& source);

/// The part folder of a bench: results.csv with the rows of `part` (its cases, global scenes)
/// and part.json (of `job`, bench_job's), whose payload holds the shard's case numbers `items`,
/// their exact results, the references of the scenes the shard ran and its workers. Into the
/// temporary folder `tmp`.
void write_bench_part(const BenchOutcome& part, const std::vector<std::size_t>& items,
                      const nlohmann::json& job, Shard shard, std::size_t total,
                      const std::filesystem::path& tmp, const std::filesystem::path& output);

/// The folder kind of a bench part (part.json beside results.csv).
OutputFolderKind bench_part_kind();

}  // namespace tumble::app
