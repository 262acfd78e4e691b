#pragma once
/// @file `tumble farm slurm|parallel`'s job: a tumble command (render, compare, bench,
/// stability, inspect) cut into N shards run by Slurm (an array job, then a merge job) or GNU
/// parallel (over ssh hosts or local slots, then the merge). The script is printed, or with
/// `submit` (Slurm) or `run` (parallel) run. Docs: docs/farm.md.

#include <filesystem>
#include <functional>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "app/farm/farm_scripts.hpp"

namespace tumble::app {

/// What `tumble farm` was asked to do.
struct FarmOptions {
  std::string engine;                ///< "slurm" or "parallel"
  std::vector<std::string> command;  ///< the words after `--`
  std::optional<int> shards;
  std::string tumble;  ///< the executable the workers run (default: this one)
  bool assume_shared = false;
  SlurmResources slurm;
  bool submit = false;
  bool wait = false;
  ParallelSlots slots;
  bool run = false;
};

/// The files a scene names besides itself (its meshes), which must reach the workers too. The
/// caller reads the scene (farm knows no scene format); empty: no scene is read.
using SceneMeshes =
    std::function<std::vector<std::filesystem::path>(const std::filesystem::path& scene)>;

/// Shards the job of options.command (relative paths from the working directory): checks the
/// command, the shard count (--shards N, or with parallel on this machine alone its job slots
/// or the cores) and that the workers can reach every path (warnings on `err`; remote workers
/// and paths on local filesystems fail unless options.assume_shared), then prints the Slurm
/// script or the parallel command line on `out`, or submits (and with `wait` waits) or runs it.
/// Returns kExitDone. Throws tumble::InputError (bad option or command, an unreachable path,
/// sbatch or a job failing).
int run_farm_job(const FarmOptions& options, const SceneMeshes& meshes_of, std::ostream& out,
                 std::ostream& err);

}  // namespace tumble::app
