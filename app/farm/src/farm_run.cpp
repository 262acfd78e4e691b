// `tumble farm slurm|parallel`'s job: the command parsed into a farm job, the workers' executable
// and the shard count decided, the paths checked, then the script printed or run.
#include "app/farm/farm_run.hpp"

#include <algorithm>
#include <chrono>
#include <ostream>
#include <system_error>
#include <thread>

#include "app/farm/farm_job.hpp"
#include "app/farm/farm_paths.hpp"
#include "app/farm/farm_slurm_run.hpp"
#include "app/farm/shard.hpp"
#include "app/support/exit_status.hpp"
#include "base/errors.hpp"
#include "base/process.hpp"

namespace tumble::app {
namespace {

/// The executable the workers run: --tumble, the one named before the command, or this one.
std::filesystem::path worker_tumble(const FarmOptions& options, const FarmJob& job) {
  const std::filesystem::path cwd = std::filesystem::current_path();
  if (!options.tumble.empty()) return (cwd / options.tumble).lexically_normal();
  if (!job.tumble.empty()) return job.tumble;
  std::error_code error;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error) throw InputError("cannot tell where this tumble is; give --tumble PATH");
  return self;
}

/// The meshes the job's scenes name (they must reach the workers too), read by `meshes_of`.
std::vector<std::filesystem::path> job_scene_meshes(const FarmJob& job,
                                                    const SceneMeshes& meshes_of) {
  std::vector<std::filesystem::path> meshes;
  if (job.command == "inspect" || !meshes_of) return meshes;
  for (const auto& input : job.inputs) {
    std::error_code error;
    if (!std::filesystem::is_regular_file(input, error)) continue;
    for (const auto& file : meshes_of(input)) {
      meshes.push_back(std::filesystem::absolute(file).lexically_normal());
    }
  }
  return meshes;
}

/// Whether the workers may be other machines: Slurm, or parallel over ssh hosts.
bool remote_workers(const FarmOptions& options) {
  if (options.engine == "slurm") return true;
  for (const std::string& host : options.slots.hosts) {
    if (host != ":") return true;
  }
  return false;
}

void check_paths(const FarmOptions& options, const JobPaths& paths, std::ostream& err) {
  check_job_paths(paths);
  if (options.assume_shared || !remote_workers(options)) return;
  bool local = false;
  const std::vector<std::string> notes = sharing_notes(paths, local);
  for (const std::string& note : notes) {
    err << "tumble farm " << options.engine << ": warning: " << note << "\n";
  }
  if (local) {
    throw InputError(
        "the paths above on local filesystems must be on one the workers share (NFS, Lustre, "
        "...); give --assume-shared if every worker sees them (a one-node cluster)");
  }
}

int shard_count(const FarmOptions& options) {
  if (options.shards) return *options.shards;
  if (options.engine == "parallel" && options.slots.hosts.empty()) {
    const int jobs =
        options.slots.jobs.value_or(static_cast<int>(std::thread::hardware_concurrency()));
    return std::max(1, jobs);
  }
  throw InputError("--shards N is required" +
                   std::string(options.engine == "slurm" ? "" : " with -S hosts"));
}

int run_slurm(const FarmOptions& options, const FarmJob& job, const std::filesystem::path& tumble,
              int shards, std::ostream& out) {
  check_slurm_resources(options.slurm);
  if (options.wait && !options.submit) throw InputError("--wait needs --submit");
  if (!options.submit) {
    out << slurm_submit_script(job, tumble, shards, options.slurm);
    return kExitDone;
  }
  const SlurmJobIds ids = submit_slurm_job(job, tumble, shards, options.slurm);
  out << "shards: Slurm job " << ids.shards << "; merge: Slurm job " << ids.merge << "\n"
      << std::flush;
  if (options.wait) {
    wait_for_slurm_job(job, ids, std::chrono::milliseconds(500));
    out << "merged: " << job.output.string() << "\n";
  }
  return kExitDone;
}

int run_parallel(const FarmOptions& options, const FarmJob& job,
                 const std::filesystem::path& tumble, int shards, std::ostream& out) {
  const std::string line = parallel_command_line(job, tumble, shards, options.slots);
  if (!options.run) {
    out << line << "\n";
    return kExitDone;
  }
  out << std::flush;
  const int status = run_attached({"bash", "-c", line}).shell_status();
  if (status == 127) throw InputError("cannot run bash (or GNU parallel: install parallel)");
  if (status != 0) {
    throw InputError("the shards or the merge failed (exit status " + std::to_string(status) +
                     "); the parts so far are in '" + parts_folder(job).string() + "'");
  }
  return kExitDone;
}

}  // namespace

int run_farm_job(const FarmOptions& options, const SceneMeshes& meshes_of, std::ostream& out,
                 std::ostream& err) {
  if (options.command.empty()) {
    throw InputError(
        "no tumble command: give it after '--', e.g. -- tumble render SCENE -o OUT.mp4");
  }
  const FarmJob job = parse_farm_job(options.command, std::filesystem::current_path());
  const std::filesystem::path tumble = worker_tumble(options, job);
  const int shards = shard_count(options);
  check_paths(options, job_paths(job, tumble, job_scene_meshes(job, meshes_of)), err);
  return options.engine == "slurm" ? run_slurm(options, job, tumble, shards, out)
                                   : run_parallel(options, job, tumble, shards, out);
}

}  // namespace tumble::app
