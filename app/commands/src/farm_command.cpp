// `tumble farm slurm|parallel`: the options; the job is app/farm/farm_run.hpp.
#include "app/commands/farm_command.hpp"

#include <filesystem>
#include <ostream>

#include <CLI/CLI.hpp>

#include "app/farm/shard.hpp"
#include "app/scene/scene.hpp"
#include "app/support/exit_status.hpp"

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
    return run_farm_job(
        options, [](const std::filesystem::path& scene) { return scene_inputs(load_scene(scene)); },
        out, err);
  });
}

}  // namespace tumble::app
