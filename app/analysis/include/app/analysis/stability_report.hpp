#pragma once
/// @file The outputs of `tumble stability` from its runs: stability.csv (one row per run), the
/// markdown report (the classification rules, then one matrix of outcomes per case) and the
/// heat map's panels (app/analysis/stability_plot.hpp draws them).
///
/// `runs` holds every run of the sweep in its order: case by case, integrator by integrator
/// (in the order of `integrators`), dt by dt (in the order of the case's dts).

#include <string>
#include <vector>

#include "app/analysis/stability_plot.hpp"
#include "app/analysis/stability_runner.hpp"
#include "app/analysis/stability_suite.hpp"
#include "engine/dynamics/integrators.hpp"

namespace tumble::app {

/// stability.csv: a header, then one row per run; the invariant columns are empty where the
/// invariant does not apply or the run was skipped. `suite` may be empty (scene cases only).
std::string stability_csv(const std::string& suite, const std::vector<StabilityCase>& cases,
                          const std::vector<StabilityRun>& runs);

/// stability.md: titled with the suite (when there is one), the classification rules, then per
/// case its description and a matrix (rows integrators, columns dt or rate x dt) of outcomes.
std::string stability_markdown(const std::string& suite, const std::vector<StabilityCase>& cases,
                               const std::vector<engine::IntegratorInfo>& integrators,
                               const std::vector<StabilityRun>& runs);

/// One heat map panel per case, with the markdown's rows and columns.
std::vector<HeatMapPanel> stability_heat_map(const std::vector<StabilityCase>& cases,
                                             const std::vector<engine::IntegratorInfo>& integrators,
                                             const std::vector<StabilityRun>& runs);

}  // namespace tumble::app
