#pragma once
/// @file Submitting a farmed job to Slurm (`tumble farm slurm --submit`) and waiting for it
/// (`--wait`), through sbatch, scontrol and scancel.

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "app/farm/farm_scripts.hpp"

namespace tumble::app {

struct SlurmJobIds {
  std::string shards;  ///< the array job
  std::string merge;   ///< the merge job, afterok the array job
};

/// The job id of `sbatch --parsable`'s output ("12" or "12;cluster"); throws InputError
/// quoting it when it is not one.
std::string parsable_job_id(const std::string& output);

/// The JobState of each record of `scontrol show job -o` output, in order.
std::vector<std::string> job_states(const std::string& scontrol_output);
/// The ArrayTaskId of each record ("" where there is none), in the order of job_states.
std::vector<std::string> array_task_ids(const std::string& scontrol_output);
/// Whether `state` is one a job leaves no more (COMPLETED, FAILED, CANCELLED, TIMEOUT, ...).
bool final_job_state(const std::string& state);

/// Creates OUT.parts, writes the two scripts there (shards.sbatch, merge.sbatch) and submits
/// them: sbatch --parsable for the array, then for the merge with --dependency=afterok.
/// Throws InputError with sbatch's last line when it fails.
SlurmJobIds submit_slurm_job(const FarmJob& job, const std::filesystem::path& tumble, int shards,
                             const SlurmResources& resources);

/// Waits until the merge job has ended, polling scontrol every `poll`. Returns when it
/// completed; throws InputError when it failed (with its log's last line), or when a shard
/// task failed, in which case the merge job (which would never start) is cancelled first.
void wait_for_slurm_job(const FarmJob& job, const SlurmJobIds& ids, std::chrono::milliseconds poll);

}  // namespace tumble::app
