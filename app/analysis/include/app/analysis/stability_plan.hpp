#pragma once
/// @file What `tumble stability` and `tumble merge` share: the plan of a sweep (its integrators
/// and cases, whose runs are made case by case, integrator by integrator, dt by dt) and the output
/// folder written from the runs, so that a merged sweep is the unsharded one.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "app/analysis/stability_options.hpp"
#include "app/analysis/stability_runner.hpp"
#include "app/analysis/stability_suite.hpp"
#include "app/support/output_folder.hpp"
#include "engine/dynamics/integrators.hpp"

namespace tumble::app {

/// The integrators --integrators names (each name checked), or every one.
std::vector<engine::IntegratorInfo> parse_stability_integrators(
    const std::optional<std::string>& text);

/// The cases to run: the suite's (filtered by --cases), then the scene files; `suite_name` is
/// set to the suite's name (empty when only scenes run).
std::vector<StabilityCase> gather_stability_cases(const StabilityOptions& options,
                                                  std::string& suite_name);

/// The number of runs of the sweep: cases x integrators x each case's dts.
std::size_t stability_run_count(const std::vector<StabilityCase>& cases, std::size_t integrators);

/// A stability output: stability.md under its title (and the suite), beside stability.csv.
extern const OutputFolderKind kStabilityOutput;

/// Writes the CSV, the markdown report and the heat map into the temporary folder `temporary`;
/// a failed write is named by its final name in `output` (nothing is written there).
void write_stability_folder(const std::string& suite, const std::vector<StabilityCase>& cases,
                            const std::vector<engine::IntegratorInfo>& integrators,
                            const std::vector<StabilityRun>& runs,
                            const std::filesystem::path& temporary,
                            const std::filesystem::path& output);

}  // namespace tumble::app
