#pragma once
/// @file The job scripts of `tumble farm`: a Slurm array job (one task per shard) with a merge
/// job depending on it, or a GNU parallel command line followed by the merge. Text only; running
/// them is farm_command's (app/commands/src/farm_command.cpp).
///
/// Every script is for bash, and every word in it is quoted for bash (shell_quote), so paths
/// with spaces, quotes or '$' reach tumble as they are.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "app/farm/farm_job.hpp"

namespace tumble::app {

/// `word` as one bash word: as it is when it holds only [A-Za-z0-9_@%+=:,./-] (and is not
/// empty), otherwise in single quotes ('it'\''s').
std::string shell_quote(std::string_view word);

/// What an array task or the merge asks Slurm for; empty: the cluster's default.
struct SlurmResources {
  std::string job_name;  ///< default: tumble-COMMAND-OUTNAME
  std::string partition;
  std::string time;  ///< minutes, MM:SS, HH:MM:SS, D-HH, D-HH:MM or D-HH:MM:SS
  std::optional<int> cpus_per_task;
  std::string mem;  ///< per node: N with an optional K, M, G or T
  std::string account;
  std::optional<int> max_running;  ///< array tasks at once (--array=0-N%K)
};

/// Checks each resource's form; throws InputError naming the option ("--time: expected ...").
void check_slurm_resources(const SlurmResources& resources);

/// The job name: `resources.job_name`, or tumble-COMMAND-OUTNAME with characters outside
/// [A-Za-z0-9._-] made '_'.
std::string slurm_job_name(const FarmJob& job, const SlurmResources& resources);

/// The words of shard `index` of `shards` (a shell expression, e.g. "$SLURM_ARRAY_TASK_ID"),
/// as bash: TUMBLE COMMAND ARGS --shard INDEX/N -o OUT.parts/part-INDEX.EXT. `index` is left
/// unquoted where it stands, everything else is quoted.
std::string shard_command(const FarmJob& job, const std::filesystem::path& tumble,
                          std::string_view index, int shards);
/// TUMBLE merge OUT.parts/part-{0..N-1}.EXT -o OUT, as bash.
std::string merge_command(const FarmJob& job, const std::filesystem::path& tumble, int shards);

/// The sbatch script of the shards: #SBATCH --array=0-(N-1) and the resources, and the task.
std::string slurm_array_script(const FarmJob& job, const std::filesystem::path& tumble, int shards,
                               const SlurmResources& resources);
/// The sbatch script of the merge (job name NAME-merge; partition, account and time only).
std::string slurm_merge_script(const FarmJob& job, const std::filesystem::path& tumble, int shards,
                               const SlurmResources& resources);
/// The sbatch options given on the command line, not in the script, because they name paths
/// (#SBATCH lines cannot quote): --output=OUT.parts/slurm-%A_%a.out (or slurm-%j-merge.out).
std::vector<std::string> slurm_log_option(const FarmJob& job, bool merge);
/// A bash script that submits both: creates OUT.parts, submits the array job with sbatch
/// --parsable, then the merge job with --dependency=afterok:ARRAY, each script given on
/// standard input, and prints the two job ids.
std::string slurm_submit_script(const FarmJob& job, const std::filesystem::path& tumble, int shards,
                                const SlurmResources& resources);

/// Where GNU parallel runs the shards: `hosts` for -S (empty: this machine), `jobs` per host
/// (none: parallel's default, one per core).
struct ParallelSlots {
  std::vector<std::string> hosts;
  std::optional<int> jobs;
};

/// One bash command line: mkdir -p OUT.parts && parallel -q [--jobs K] [-S HOSTS] --halt
/// now,fail=1 SHARD-COMMAND ::: {0..N-1} && MERGE-COMMAND.
std::string parallel_command_line(const FarmJob& job, const std::filesystem::path& tumble,
                                  int shards, const ParallelSlots& slots);

}  // namespace tumble::app
