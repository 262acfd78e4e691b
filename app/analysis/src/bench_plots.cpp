// The work-precision plots of `tumble bench`: per scene and error measure, error against run
// time (median, with the min-max spread of the repeats as a bar) and error against
// right-hand-side evaluations; one colour and marker per integrator in every plot.
#include <algorithm>
#include <cstdint>

#include "app/analysis/bench_report.hpp"
#include "app/analysis/gnuplot.hpp"
#include "engine/dynamics/integrators.hpp"

namespace tumble::app {
namespace {

/// One plot of scene `s`: `measure` against run time or against evaluations.
LogLogPlot measure_plot(const BenchOutcome& outcome, std::size_t s, const ErrorMeasure& measure,
                        bool against_evaluations, const std::filesystem::path& dir) {
  const BenchScene& scene = outcome.scenes[s];
  LogLogPlot plot;
  plot.file_stem =
      dir / (scene.label + "_" + measure.suffix + (against_evaluations ? kEvaluationsSuffix : ""));
  plot.title = scene.name + ": " + measure.label + " against " +
               (against_evaluations ? "right-hand-side evaluations" : "run time");
  plot.x_label = against_evaluations
                     ? "right-hand-side evaluations (forces and rotational rate), all bodies"
                     : "run time of the stepping loop (s, median; bar: min to max)";
  plot.y_label = measure.label;
  plot.x_error_bars = !against_evaluations;
  // One line per integrator, its runs ordered along x; blow-ups are left out.
  for (const std::string& name : integrators_of(outcome, s)) {
    PlotSeries series{name, {}, integrator_style(name)};
    for (std::size_t i = 0; i < outcome.cases.size(); ++i) {
      const BenchCase& c = outcome.cases[i];
      const CaseResult& r = outcome.results[i];
      if (c.scene != s || c.integrator != name || r.blow_up_time) continue;
      const double y = r.errors.*measure.field;
      if (against_evaluations) {
        series.points.push_back({static_cast<double>(r.counts.evaluations), y});
      } else {
        series.points.push_back({r.median_seconds, y, r.min_seconds, r.max_seconds});
      }
    }
    std::sort(series.points.begin(), series.points.end(),
              [](const PlotPoint& a, const PlotPoint& b) { return a.x < b.x; });
    plot.series.push_back(std::move(series));
  }
  return plot;
}

}  // namespace

PlotStyle integrator_style(const std::string& name) {
  // Twelve colours and eleven markers (coprime counts): the catalog's first 132 integrators
  // each get their own pair, by catalog position, whatever else a run or plot holds.
  static const char* const kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e",
                                         "#9467bd", "#8c564b", "#e377c2", "#7f7f7f",
                                         "#bcbd22", "#17becf", "#000000", "#0b5d1e"};
  static const int kPointTypes[] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 12, 13};
  std::size_t index = 0;
  const auto& catalog = engine::integrator_catalog();
  const auto it =
      std::find_if(catalog.begin(), catalog.end(),
                   [&](const engine::IntegratorInfo& info) { return info.name == name; });
  if (it != catalog.end()) {
    index = static_cast<std::size_t>(it - catalog.begin());
  } else {
    // Not in the catalog: a fixed hash of the name (FNV-1a), the same in every run.
    std::uint64_t hash = 14695981039346656037ull;
    for (char c : name) hash = (hash ^ static_cast<unsigned char>(c)) * 1099511628211ull;
    index = static_cast<std::size_t>(hash % 1000);
  }
  return {kColours[index % std::size(kColours)], kPointTypes[index % std::size(kPointTypes)]};
}

const std::vector<ErrorMeasure>& plotted_measures() {
  static const std::vector<ErrorMeasure> measures = {
      {"orientation_final", "final orientation error (rad)", &ErrorFigures::orientation_final},
      {"orientation_max", "max orientation error (rad)", &ErrorFigures::orientation_max},
      {"omega_max", "max relative error of world omega", &ErrorFigures::omega_max},
      {"momentum_max", "max relative error of world L", &ErrorFigures::momentum_max},
      {"energy_drift", "max relative energy drift", &ErrorFigures::energy_drift_max},
      {"momentum_norm_drift", "max relative |L| drift", &ErrorFigures::momentum_norm_drift_max},
  };
  return measures;
}

std::vector<LogLogPlot> bench_plots(const BenchOutcome& outcome, const std::filesystem::path& dir) {
  std::vector<LogLogPlot> plots;
  for (std::size_t s = 0; s < outcome.scenes.size(); ++s) {
    for (const ErrorMeasure& measure : plotted_measures()) {
      plots.push_back(measure_plot(outcome, s, measure, false, dir));
      plots.push_back(measure_plot(outcome, s, measure, true, dir));
    }
  }
  return plots;
}

void write_plots(const BenchOutcome& outcome, const std::filesystem::path& dir) {
  draw_plots(bench_plots(outcome, dir), dir / "plots.gnuplot");
}

}  // namespace tumble::app
