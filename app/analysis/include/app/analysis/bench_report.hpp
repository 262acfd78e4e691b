#pragma once
// The outputs of `tumble bench`: results.csv, the work-precision plots and report.md. Every
// writer checks every write (and gnuplot's pictures, which gnuplot itself does not): a failed
// one throws WriteError (app/support/file_write.hpp) naming the file.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "app/analysis/bench_runner.hpp"
#include "app/analysis/gnuplot.hpp"

namespace tumble::app {

/// The workers of one run of cases: threads pinned one per core.
struct BenchWorkers {
  std::size_t workers = 0;
  std::vector<int> cores_used;
  std::size_t cores_available = 0;
};

/// Everything the outputs are made from.
struct BenchOutcome {
  std::vector<BenchScene> scenes;
  std::vector<BenchCase> cases;
  std::vector<CaseResult> results;  ///< one per case
  int repeat = 0;
  std::size_t workers = 0;  ///< worker threads, one pinned core each
  std::vector<int> cores_used;
  std::size_t cores_available = 0;
  /// Merged from shards (`tumble merge`): each shard's workers, in shard order (the report
  /// then says so instead of naming one run's cores); empty for one run.
  std::vector<BenchWorkers> shards;
};

/// The columns of results.csv, in order.
const std::vector<std::string>& results_columns();

/// The integrators of scene `scene`'s cases, in order of first appearance (the row order of
/// the report and the curve order of the plots).
std::vector<std::string> integrators_of(const BenchOutcome& outcome, std::size_t scene);

/// results.csv's text: a header, then one row per case of `outcome.cases` (see
/// write_results_csv).
std::string results_csv(const BenchOutcome& outcome);

/// Writes results.csv: a header, then one row per case (17 significant digits; the error
/// columns are empty for blown-up runs).
void write_results_csv(const BenchOutcome& outcome, const std::filesystem::path& file);

/// An error measure plotted per scene: column name, file suffix, axis label.
struct ErrorMeasure {
  std::string suffix;  ///< in the plot file name: <scene>_<suffix>.png
  std::string label;
  double ErrorFigures::*field;
};
const std::vector<ErrorMeasure>& plotted_measures();

/// The suffix of the plots against right-hand-side evaluations: <scene>_<measure>_evaluations.
inline constexpr const char* kEvaluationsSuffix = "_evaluations";

/// The colour and marker of an integrator in every plot: fixed by its name (its catalog
/// position), so the same in every plot of a run and across runs.
PlotStyle integrator_style(const std::string& name);

/// The plots of every scene and measure: against run time (DIR/<scene>_<measure>) and against
/// evaluations (DIR/<scene>_<measure>_evaluations); exposed for tests.
std::vector<LogLogPlot> bench_plots(const BenchOutcome& outcome, const std::filesystem::path& dir);

/// Draws the bench_plots as .png and .svg (gnuplot).
void write_plots(const BenchOutcome& outcome, const std::filesystem::path& dir);

/// The observed order of one integrator on one scene.
struct OrderFit {
  std::optional<double> slope;  ///< of log error against log dt (log tolerance for dopri)
  std::size_t used = 0;         ///< runs in the fit
  std::size_t dropped = 0;      ///< blown up, at the rounding floor or saturated
  /// The errors are at rounding (no slope then): every run at the floor, or the fitted errors
  /// not falling with the step while each is below its run's rounding level.
  bool at_rounding = false;
};

/// Errors at or below this are at the rounding floor (the order fit drops them), rad.
inline constexpr double kRoundingFloor = 1e-11;
/// The rounding level of a run of n steps per body: rounding errors accumulate about linearly
/// with the steps, and 1e3 machine epsilons per step allow for the operations of a step, rad.
inline constexpr double kRoundingPerStep = 1e3 * 2.220446049250313e-16;
/// Orientation errors above this are out of the asymptotic range (the order fit drops them).
inline constexpr double kSaturation = 0.5;

/// Least-squares slope of log(final orientation error) against log(dt) over the runs of
/// `integrator` on `scene` that lie in the asymptotic range; none when the errors are at
/// rounding (see OrderFit::at_rounding).
OrderFit observed_order(const BenchOutcome& outcome, std::size_t scene,
                        const std::string& integrator);

/// Writes report.md.
void write_report(const BenchOutcome& outcome, const std::filesystem::path& file);

}  // namespace tumble::app
