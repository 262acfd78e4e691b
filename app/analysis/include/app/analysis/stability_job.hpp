#pragma once
/// @file `tumble stability` as library calls: the sweep (cases x integrators x dts; a shard's
/// runs only) run into classified rows, and the whole command that writes the output folder or
/// the part.

#include <functional>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "app/analysis/stability_options.hpp"
#include "app/analysis/stability_runner.hpp"
#include "app/analysis/stability_suite.hpp"
#include "app/farm/shard.hpp"
#include "engine/dynamics/integrators.hpp"

namespace tumble::app {

/// Runs every case under every integrator at each of its dts, in the order the outputs read
/// them (stability_report.hpp), with one progress line per case on `progress` when given; with
/// a shard, only the runs of that shard (every N-th of the sweep), a case's reference only when
/// one of its runs is the shard's. Stops early, with the runs so far, when `stop` says so.
std::vector<StabilityRun> run_stability_sweep(
    const std::vector<StabilityCase>& cases, const std::vector<engine::IntegratorInfo>& integrators,
    const std::optional<Shard>& shard, const std::function<bool()>& stop = {},
    std::ostream* progress = nullptr);

/// The sweep `options` asks for (suite, cases, scenes, integrators, dts; its shard's runs only)
/// run into rows (the runs of stability.csv, in its order); nothing is written. Throws
/// InputError for bad options or scenes.
std::vector<StabilityRun> run_stability_rows(const StabilityOptions& options,
                                             const std::function<bool()>& stop = {});

/// The built-in suites, one "NAME  DESCRIPTION" line each.
void list_stability_suites(std::ostream& out);

/// The whole `tumble stability`: checks, runs and writes -o DIR (stability.csv, .md, heat map;
/// with --shard the part), progress on `err` and the summary on `out`. Returns 0, or
/// kExitInterrupted (nothing written) when `interrupted` said so.
int write_stability(const StabilityOptions& options, const std::function<bool()>& interrupted,
                    std::ostream& out, std::ostream& err);

}  // namespace tumble::app
