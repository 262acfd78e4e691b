#pragma once
/// @file A shard of `tumble stability` (`--shard I/N`): the job its manifest names, and its runs
/// (every N-th of the sweep) kept exactly in the manifest's payload beside stability.csv, so that
/// `tumble merge` rebuilds the whole sweep's report and heat map bit for bit.

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/analysis/stability_options.hpp"
#include "app/analysis/stability_runner.hpp"
#include "app/farm/part_manifest.hpp"
#include "app/support/output_folder.hpp"

namespace tumble::app {

/// The stability job: the command, each scene with its and its meshes' digests, and the options
/// that change the output (suite, cases, integrators, dts), never --shard or -o.
nlohmann::json stability_job(const StabilityOptions& options);

/// The options of `job` (stability_job's), after checking that the scenes are unchanged.
StabilityOptions stability_job_options(const nlohmann::json& job);

/// A run as JSON (every double exact) and back; the latter throws InputError naming `source`.
nlohmann::json stability_run_json(const StabilityRun& run);
StabilityRun stability_run_from_json(const nlohmann::json& json, const std::string& source);

/// The part folder of a sweep's shard: stability.csv with `runs` (the shard's, in order) and
/// part.json of `job`, whose payload holds the run numbers `items` and the exact runs.
void write_stability_part(const std::string& suite, const std::vector<StabilityCase>& cases,
                          const std::vector<StabilityRun>& runs,
                          const std::vector<std::size_t>& items, const nlohmann::json& job,
                          Shard shard, std::size_t total, const std::filesystem::path& tmp,
                          const std::filesystem::path& output);

/// The folder kind of a stability part (part.json beside stability.csv).
OutputFolderKind stability_part_kind();

}  // namespace tumble::app
