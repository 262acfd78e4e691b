#pragma once
/// @file `tumble bench` as library calls: the plan of a bench (its cases; a shard's only), its
/// run (references, then every case on pinned workers) into rows, and the whole command that
/// writes the output folder or the part.

#include <cstddef>
#include <functional>
#include <iosfwd>
#include <optional>
#include <vector>

#include "app/analysis/bench_options.hpp"
#include "app/analysis/bench_report.hpp"
#include "app/farm/shard.hpp"

namespace tumble::app {

/// A planned bench: the outcome's scenes, cases (with a shard, only its own) and repeat; its
/// results once run.
struct BenchRun {
  BenchOutcome outcome;
  std::size_t jobs = 1;            ///< workers asked for (capped at the cores when run)
  std::optional<Shard> shard;      ///< --shard
  std::vector<std::size_t> items;  ///< a shard's case numbers in the whole plan
  std::size_t total = 0;           ///< cases of the whole plan
};

/// Checks --repeat, --jobs and --shard (cheap: no scene is read). Throws InputError naming the
/// option.
BenchRun bench_settings(const BenchOptions& options);

/// Loads the scenes and lays out every case in results.csv's order, keeping a shard's only.
/// Throws InputError for bad options or scenes.
void plan_bench_run(const BenchOptions& options, BenchRun& run);

/// Computes the references of the scenes the cases use, then runs the cases, filling
/// run.outcome.results and its workers; a line per finished case on `progress` when given (a
/// bar on a terminal). Returns false when `stop` said so (the results are then incomplete).
bool run_bench_cases(BenchRun& run, const std::function<bool()>& stop = {},
                     std::ostream* progress = nullptr);

/// The three above: the bench of `options` run, its rows (outcome.results, one per case, the
/// numbers of results.csv) returned; nothing is written. Empty when `stop` said so.
std::optional<BenchOutcome> run_bench_rows(const BenchOptions& options,
                                           const std::function<bool()>& stop = {});

/// The whole `tumble bench`: checks, plans, runs and writes -o DIR (results.csv, plots,
/// report.md; with --shard the part), printing progress on `err` and the summary on `out`.
/// Returns 0, or kExitInterrupted (nothing written) when `interrupted` said so.
int write_bench(const BenchOptions& options, const std::function<bool()>& interrupted,
                std::ostream& out, std::ostream& err);

}  // namespace tumble::app
