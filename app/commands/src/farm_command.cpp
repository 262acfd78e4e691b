#include "app/commands/farm_command.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <thread>

#include <CLI/CLI.hpp>

#include "app/farm/farm_paths.hpp"
#include "app/farm/farm_slurm_run.hpp"
#include "app/farm/shard.hpp"
#include "app/scene/scene.hpp"
#include "app/support/exit_status.hpp"
#include "base/process.hpp"

namespace tumble::app {

namespace {

void add_common_options(CLI::App& engine, FarmOptions& options) {
  engine.add_option("--shards", options.shards, "Number of shards N (each a part of the job)")
      ->type_name("N")
      ->check(CLI::Range(1, kMaxShards));
  engine
      .add_option("--tumble", options.tumble,
                  "The tumble executable the workers run (default: this one), an absolute "
                  "path that is the same on every worker")
      ->type_name("PATH");
  engine.add_flag("--assume-shared", options.assume_shared,
                  "Take every path as seen by the workers (a one-node cluster, or a shared "
                  "filesystem tumble does not recognise): no filesystem check");
  engine.add_option("COMMAND", options.command,
                    "After '--': the tumble command, e.g. tumble render SCENE -o OUT.mp4");
}

void add_slurm_options(CLI::App& slurm, FarmOptions& options) {
  SlurmResources& r = options.slurm;
  slurm.add_option("--job-name", r.job_name, "Slurm job name (default tumble-COMMAND-OUTNAME)");
  slurm.add_option("--partition", r.partition, "Slurm partition (default: the cluster's)");
  slurm.add_option("--time", r.time, "Time limit of each task and of the merge (D-HH:MM:SS...)");
  slurm.add_option("--cpus-per-task", r.cpus_per_task, "CPUs of each shard task")->type_name("C");
  slurm.add_option("--mem", r.mem, "Memory of each shard task (e.g. 4G)");
  slurm.add_option("--account", r.account, "Slurm account to charge");
  slurm.add_option("--max-running", r.max_running, "At most K shard tasks at once (--array=...%K)")
      ->type_name("K");
  slurm.add_flag("--submit", options.submit,
                 "Submit the two jobs with sbatch and print their ids, instead of the script");
  slurm.add_flag("--wait", options.wait,
                 "With --submit: wait until the merge has ended (fails if a shard failed)");
}

void add_parallel_options(CLI::App& parallel, FarmOptions& options) {
  parallel
      .add_option_function<std::string>(
          "-S,--hosts",
          [&options](const std::string& list) {
            std::size_t begin = 0;
            for (std::size_t comma; (comma = list.find(',', begin)) != std::string::npos;
                 begin = comma + 1) {
              options.slots.hosts.push_back(list.substr(begin, comma - begin));
            }
            options.slots.hosts.push_back(list.substr(begin));
          },
          "ssh hosts for GNU parallel, comma-separated; ':' is this machine (default: only "
          "this machine)")
      ->type_name("HOST,...");
  parallel
      .add_option("--jobs", options.slots.jobs,
                  "Shards at once on each host (default: GNU parallel's, one per core)")
      ->type_name("K");
  parallel.add_flag("--run", options.run, "Run the command line instead of printing it");
}

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

/// The meshes the job's scenes name (they must reach the workers too).
std::vector<std::filesystem::path> scene_meshes(const FarmJob& job) {
  std::vector<std::filesystem::path> meshes;
  if (job.command == "inspect") return meshes;
  for (const auto& input : job.inputs) {
    std::error_code error;
    if (!std::filesystem::is_regular_file(input, error)) continue;
    for (const auto& file : scene_inputs(load_scene(input))) {
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

CLI::App& add_farm_command(CLI::App& cli, FarmOptions& options) {
  CLI::App& farm = *cli.add_subcommand(
      "farm",
      "Cut a render, compare, bench, stability or inspect into shards run by Slurm or GNU "
      "parallel, then merged: prints the script (docs/farm.md)");
  farm.require_subcommand(1);
  CLI::App& slurm = *farm.add_subcommand(
      "slurm", "A Slurm array job (one task per shard) and a merge job after it (afterok)");
  CLI::App& parallel = *farm.add_subcommand(
      "parallel", "One GNU parallel command line over ssh hosts or local slots, then the merge");
  for (CLI::App* engine : {&slurm, &parallel}) add_common_options(*engine, options);
  add_slurm_options(slurm, options);
  add_parallel_options(parallel, options);
  slurm.callback([&options] { options.engine = "slurm"; });
  parallel.callback([&options] { options.engine = "parallel"; });
  return farm;
}

int run_farm(const FarmOptions& options, std::ostream& out, std::ostream& err) {
  return run_guarded("farm " + options.engine, err, [&] {
    if (options.command.empty()) {
      throw InputError(
          "no tumble command: give it after '--', e.g. -- tumble render SCENE -o "
          "OUT.mp4");
    }
    const FarmJob job = parse_farm_job(options.command, std::filesystem::current_path());
    const std::filesystem::path tumble = worker_tumble(options, job);
    const int shards = shard_count(options);
    check_paths(options, job_paths(job, tumble, scene_meshes(job)), err);
    return options.engine == "slurm" ? run_slurm(options, job, tumble, shards, out)
                                     : run_parallel(options, job, tumble, shards, out);
  });
}

}  // namespace tumble::app
