#include "app/analysis/bench_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>
#include <stdexcept>

#include "app/analysis/gnuplot.hpp"
#include "app/support/file_write.hpp"

namespace tumble::app {
namespace {

std::string number(double value, const char* format = "%.17g") {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

std::string csv_text(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

/// "dt 0.01" or "tol 1e-08".
std::string step_text(const BenchCase& c) {
  return c.tolerance ? "tol " + number(*c.tolerance, "%.3g") : "dt " + number(c.dt, "%.4g");
}

}  // namespace

// The integrators of a scene's cases, in order of first appearance.
std::vector<std::string> integrators_of(const BenchOutcome& outcome, std::size_t scene) {
  std::vector<std::string> names;
  for (const BenchCase& c : outcome.cases) {
    if (c.scene == scene && std::find(names.begin(), names.end(), c.integrator) == names.end()) {
      names.push_back(c.integrator);
    }
  }
  return names;
}

const std::vector<std::string>& results_columns() {
  static const std::vector<std::string> columns = {"scene",
                                                   "scene_file",
                                                   "integrator",
                                                   "order",
                                                   "adaptive",
                                                   "dt",
                                                   "tolerance",
                                                   "duration",
                                                   "steps",
                                                   "total_steps",
                                                   "accepted_steps",
                                                   "rejected_steps",
                                                   "evaluations",
                                                   "blew_up",
                                                   "blow_up_time",
                                                   "blow_up_reason",
                                                   "repeats",
                                                   "seconds_median",
                                                   "seconds_min",
                                                   "seconds_max",
                                                   "ns_per_step",
                                                   "core",
                                                   "samples",
                                                   "orientation_error_final",
                                                   "orientation_error_max",
                                                   "omega_error_final",
                                                   "omega_error_max",
                                                   "momentum_error_final",
                                                   "momentum_error_max",
                                                   "energy_drift_max",
                                                   "momentum_norm_drift_max"};
  return columns;
}

std::string results_csv(const BenchOutcome& outcome) {
  std::ostringstream out;
  for (std::size_t i = 0; i < results_columns().size(); ++i) {
    out << (i ? "," : "") << results_columns()[i];
  }
  out << "\n";
  for (std::size_t i = 0; i < outcome.cases.size(); ++i) {
    const BenchCase& c = outcome.cases[i];
    const CaseResult& r = outcome.results[i];
    const BenchScene& scene = outcome.scenes[c.scene];
    const bool blew_up = r.blow_up_time.has_value();
    out << csv_text(scene.label) << "," << csv_text(scene.file.string()) << "," << c.integrator
        << "," << c.order << "," << (c.adaptive ? 1 : 0) << "," << number(c.dt) << ","
        << (c.tolerance ? number(*c.tolerance) : "") << "," << number(scene.settings.duration)
        << "," << r.steps << "," << r.total_steps << "," << r.counts.accepted << ","
        << r.counts.rejected << "," << r.counts.evaluations << "," << (blew_up ? 1 : 0) << ","
        << (blew_up ? number(*r.blow_up_time) : "") << "," << csv_text(r.blow_up_reason) << ","
        << r.seconds.size() << "," << number(r.median_seconds) << ","
        << (r.seconds.empty() ? "" : number(r.min_seconds)) << ","
        << (r.seconds.empty() ? "" : number(r.max_seconds)) << ","
        << number(r.steps ? 1e9 * r.median_seconds / static_cast<double>(r.steps) : 0.0) << ","
        << r.core << "," << r.errors.samples;
    const ErrorFigures& e = r.errors;
    for (double value :
         {e.orientation_final, e.orientation_max, e.omega_final, e.omega_max, e.momentum_final,
          e.momentum_max, e.energy_drift_max, e.momentum_norm_drift_max}) {
      out << "," << (blew_up ? "" : number(value));
    }
    out << "\n";
  }
  return out.str();
}

void write_results_csv(const BenchOutcome& outcome, const std::filesystem::path& file) {
  write_text_file(file, results_csv(outcome));
}

namespace {

/// A run's steps per body: its output steps, or the accepted steps of an adaptive run.
double steps_per_body(const BenchOutcome& outcome, std::size_t i) {
  const CaseResult& r = outcome.results[i];
  const std::size_t bodies =
      std::max<std::size_t>(1, outcome.scenes[outcome.cases[i].scene].bodies.size());
  return static_cast<double>(std::max<std::size_t>({1, r.steps, r.counts.accepted / bodies}));
}

std::optional<double> least_squares_slope(const std::vector<std::pair<double, double>>& points) {
  double mx = 0.0, my = 0.0;
  for (const auto& [x, y] : points) {
    mx += x;
    my += y;
  }
  mx /= static_cast<double>(points.size());
  my /= static_cast<double>(points.size());
  double sxx = 0.0, sxy = 0.0;
  for (const auto& [x, y] : points) {
    sxx += (x - mx) * (x - mx);
    sxy += (x - mx) * (y - my);
  }
  if (!(sxx > 0.0)) return std::nullopt;
  return sxy / sxx;
}

}  // namespace

OrderFit observed_order(const BenchOutcome& outcome, std::size_t scene,
                        const std::string& integrator) {
  // Points (log step, log error) in the asymptotic range.
  OrderFit fit;
  std::vector<std::pair<double, double>> points;
  std::vector<std::pair<double, double>> saturated;
  std::size_t at_floor = 0;
  bool below_rounding_level = true;  // every fitted error below its run's rounding level
  for (std::size_t i = 0; i < outcome.cases.size(); ++i) {
    const BenchCase& c = outcome.cases[i];
    if (c.scene != scene || c.integrator != integrator) continue;
    const CaseResult& r = outcome.results[i];
    const double error = r.errors.orientation_final;
    const std::pair<double, double> point{std::log(c.tolerance ? *c.tolerance : c.dt),
                                          std::log(error)};
    if (r.blow_up_time || !(error > kRoundingFloor)) {
      ++fit.dropped;
      at_floor += !r.blow_up_time && !std::isnan(error);
    } else if (!(error < kSaturation)) {
      saturated.push_back(point);
    } else {
      points.push_back(point);
      below_rounding_level =
          below_rounding_level && error <= kRoundingPerStep * steps_per_body(outcome, i);
    }
  }
  // Saturated runs are out of the asymptotic range, unless every run is: then the integrator
  // does not converge on this sweep, and the fit over them all shows it (a slope near 0).
  if (points.empty()) {
    points = saturated;
    below_rounding_level = saturated.empty();
  } else {
    fit.dropped += saturated.size();
  }
  fit.used = points.size();
  if (points.size() < 2) {
    fit.at_rounding = at_floor > 0 && below_rounding_level;
    return fit;
  }
  fit.slope = least_squares_slope(points);
  // Errors that do not fall as the step falls, all at their runs' rounding level: rounding,
  // which grows with the number of steps, not a (negative) order.
  if (fit.slope && !(*fit.slope > 0.0) && below_rounding_level) {
    fit.slope.reset();
    fit.at_rounding = true;
  }
  return fit;
}

namespace {

/// The runs of scene `s` whose final orientation error is exactly 0.
std::size_t zero_error_runs(const BenchOutcome& outcome, std::size_t s) {
  std::size_t count = 0;
  for (std::size_t i = 0; i < outcome.cases.size(); ++i) {
    const CaseResult& r = outcome.results[i];
    count += outcome.cases[i].scene == s && !r.blow_up_time && r.errors.orientation_final == 0.0;
  }
  return count;
}

/// The smallest non-zero final orientation error of scene `s` among the runs that did not
/// blow up; infinity when there is none.
double smallest_final_error(const BenchOutcome& outcome, std::size_t s) {
  double smallest = INFINITY;
  for (std::size_t i = 0; i < outcome.cases.size(); ++i) {
    const CaseResult& r = outcome.results[i];
    if (outcome.cases[i].scene == s && !r.blow_up_time && r.errors.orientation_final > 0.0) {
      smallest = std::min(smallest, r.errors.orientation_final);
    }
  }
  return smallest;
}

/// The heading of scene `s` and its list: grid, reference and its check, invariants.
void scene_summary(std::ostream& out, const BenchOutcome& outcome, std::size_t s) {
  const BenchScene& scene = outcome.scenes[s];
  out << "## " << scene.name << " (`" << scene.file.string() << "`)\n\n"
      << "- duration " << number(scene.settings.duration, "%.6g") << " s; sampling grid every "
      << number(scene.grid.interval, "%.6g") << " s (" << scene.grid.count() << " samples)\n"
      << "- reference: " << scene.reference.description << "\n";
  const double smallest = smallest_final_error(outcome, s);
  if (const auto& check = scene.reference.check) {
    out << "- reference check (" << check->runs << "): orientation "
        << number(check->orientation, "%.2e") << " rad, world omega "
        << number(check->omega, "%.2e") << ", world L " << number(check->momentum, "%.2e")
        << " (relative)\n";
    if (std::isfinite(smallest) && check->orientation > 0.1 * smallest) {
      out << "- **warning**: the two references disagree by more than a tenth of the smallest "
             "final orientation error measured ("
          << number(smallest, "%.2e") << " rad): errors near that level are not resolved\n";
    }
  }
  if (const std::size_t zeros = zero_error_runs(outcome, s)) {
    out << "- " << zeros << " run" << (zeros == 1 ? " has" : "s have")
        << " a final orientation error of exactly 0 (drawn at the floor marker in the plots)\n";
  }
  out << "- invariants: energy " << (scene.conservative ? "is" : "is **not**") << ", |L| "
      << (scene.torque_free ? "is" : "is **not**")
      << " an invariant here (a drift of a non-invariant is not an error)\n\n";
}

/// The table of the runs of scene `s`.
void runs_table(std::ostream& out, const BenchOutcome& outcome, std::size_t s) {
  out << "| integrator | step | steps | accepted + rejected | evaluations | time (s) | time "
         "min - max (s) | ns/step | orient. final (rad) | orient. max (rad) | omega max | L max "
         "| energy drift | abs(L) drift |\n"
      << "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (std::size_t i = 0; i < outcome.cases.size(); ++i) {
    const BenchCase& c = outcome.cases[i];
    if (c.scene != s) continue;
    const CaseResult& r = outcome.results[i];
    const double per_step = r.steps ? 1e9 * r.median_seconds / static_cast<double>(r.steps) : 0;
    out << "| " << c.integrator << " | " << step_text(c) << " | " << r.steps << " | "
        << r.counts.accepted << " + " << r.counts.rejected << " | " << r.counts.evaluations << " | "
        << number(r.median_seconds, "%.3g") << " | " << number(r.min_seconds, "%.3g") << " - "
        << number(r.max_seconds, "%.3g") << " | " << number(per_step, "%.0f") << " | ";
    if (r.blow_up_time) {
      out << "blew up at t = " << number(*r.blow_up_time, "%.4g") << " s (" << r.blow_up_reason
          << ") | | | | | |\n";
      continue;
    }
    const ErrorFigures& e = r.errors;
    out << number(e.orientation_final, "%.2e") << " | " << number(e.orientation_max, "%.2e")
        << " | " << number(e.omega_max, "%.2e") << " | " << number(e.momentum_max, "%.2e") << " | "
        << number(e.energy_drift_max, "%.2e") << " | " << number(e.momentum_norm_drift_max, "%.2e")
        << " |\n";
  }
}

/// The observed order of each integrator on scene `s`, against its nominal order.
void observed_order_table(std::ostream& out, const BenchOutcome& outcome, std::size_t s) {
  out << "\n### Observed order\n\nLeast-squares slope of log(final orientation error) against "
         "log(dt) (dopri: against log(tolerance)), over the runs with an error between "
      << number(kRoundingFloor, "%.0e") << " and " << number(kSaturation, "%.2g")
      << " rad that did not blow up (when every run is above " << number(kSaturation, "%.2g")
      << " rad the integrator does not converge here, and all its runs are fitted). "
         "**n/a (rounding)**: the errors are at rounding, not a measure of the order: every run "
         "at or below "
      << number(kRoundingFloor, "%.0e")
      << " rad, or the fitted errors do not fall as the step falls (slope <= 0) while each is "
         "below its run's rounding level, 1e3 machine epsilons per step (n steps: "
      << number(kRoundingPerStep, "%.1e")
      << " n rad), e.g. free-rotor, exact without torques, whose rounding error grows with the "
         "number of steps. n/a: fewer than two runs left.\n\n| integrator | nominal order | "
         "observed | runs used | runs dropped |\n|---|---:|---:|---:|---:|\n";
  for (const std::string& name : integrators_of(outcome, s)) {
    const auto it = std::find_if(outcome.cases.begin(), outcome.cases.end(),
                                 [&](const BenchCase& c) { return c.integrator == name; });
    const OrderFit fit = observed_order(outcome, s, name);
    const std::string observed = fit.slope         ? number(*fit.slope, "%.2f")
                                 : fit.at_rounding ? "n/a (rounding)"
                                                   : "n/a";
    out << "| " << name << " | " << it->order << (it->adaptive ? " (per tolerance: 1)" : "")
        << " | " << observed << " | " << fit.used << " | " << fit.dropped << " |\n";
  }
}

/// The fastest run of scene `s` to reach each accuracy level.
void fastest_table(std::ostream& out, const BenchOutcome& outcome, std::size_t s) {
  out << "\n### Fastest to each accuracy (final orientation error)\n\n"
         "| accuracy (rad) | integrator | step | time (s) | error (rad) "
         "|\n|---|---|---|---:|---:|\n";
  for (double level : {1e-2, 1e-4, 1e-6, 1e-8, 1e-10}) {
    std::optional<std::size_t> best;
    for (std::size_t i = 0; i < outcome.cases.size(); ++i) {
      const CaseResult& r = outcome.results[i];
      if (outcome.cases[i].scene != s || r.blow_up_time || !(r.errors.orientation_final <= level))
        continue;
      if (!best || r.median_seconds < outcome.results[*best].median_seconds) best = i;
    }
    out << "| " << number(level, "%.0e") << " | ";
    if (!best) {
      out << "none reached it | | | |\n";
      continue;
    }
    const BenchCase& c = outcome.cases[*best];
    const CaseResult& r = outcome.results[*best];
    out << c.integrator << " | " << step_text(c) << " | " << number(r.median_seconds, "%.3g")
        << " | " << number(r.errors.orientation_final, "%.2e") << " |\n";
  }
}

/// Links to the work-precision diagrams of a scene.
void plot_links(std::ostream& out, const BenchScene& scene) {
  out << "\n### Work-precision diagrams\n\nEach measure against the run time (median of the "
         "repeats, the bar from the fastest to the slowest) and against the right-hand-side "
         "evaluations; one colour and marker per integrator in every plot. Blown-up runs are "
         "left out; a run whose error is exactly 0 is drawn as an open triangle at the plot's "
         "floor (a decade below its smallest non-zero error), which the plot names.\n\n";
  for (const ErrorMeasure& measure : plotted_measures()) {
    const std::string stem = scene.label + "_" + measure.suffix;
    const std::string evaluations = stem + kEvaluationsSuffix;
    out << "- " << measure.label << ": [" << stem << ".svg](" << stem << ".svg), against "
        << "evaluations [" << evaluations << ".svg](" << evaluations << ".svg)\n\n  ![" << stem
        << "](" << stem << ".png) ![" << evaluations << "](" << evaluations << ".png)\n";
  }
  out << "\n";
}

/// The scene's section of the report.
void scene_section(std::ostream& out, const BenchOutcome& outcome, std::size_t s) {
  scene_summary(out, outcome, s);
  runs_table(out, outcome, s);
  observed_order_table(out, outcome, s);
  fastest_table(out, outcome, s);
  plot_links(out, outcome.scenes[s]);
}

/// Where the timed loops ran: one run's workers, or each shard's.
std::string workers_text(const BenchOutcome& outcome) {
  std::ostringstream out;
  const auto workers = [&](const BenchWorkers& w, const char* between) {
    out << w.workers << " worker" << (w.workers == 1 ? "" : "s") << between << "(cores";
    for (int core : w.cores_used) out << " " << core;
    out << " of " << w.cores_available << " available)";
  };
  if (outcome.shards.empty()) {
    out << "Ran on ";
    workers({outcome.workers, outcome.cores_used, outcome.cores_available},
            ", each pinned to its own core ");
    out << ", so no two timed loops shared a core.\n\n";
    return out.str();
  }
  out << "Ran as " << outcome.shards.size()
      << " shards (`--shard I/N`) merged by `tumble merge`, the workers of each shard pinned one "
         "per core of its machine, so no two timed loops of a shard shared a core:";
  for (std::size_t i = 0; i < outcome.shards.size(); ++i) {
    out << (i ? ";" : "") << " shard " << i << "/" << outcome.shards.size() << " on ";
    workers(outcome.shards[i], " ");
  }
  out << ".\n\n";
  return out.str();
}

}  // namespace

void write_report(const BenchOutcome& outcome, const std::filesystem::path& file) {
  std::ostringstream out;
  out << "# tumble bench\n\n"
      << "Error against run time. Each case: one measured run (errors sampled on the scene's "
         "grid), used as the warm-up, then "
      << outcome.repeat
      << " timed runs of the stepping loop alone (Simulation::step; no sampling, no output); "
         "the time is their median, with their min and max.\n\n"
      << workers_text(outcome)
      << "Errors are sampled at every multiple of the sampling interval (the largest step of "
         "the sweep; every swept step divides it) and at the end, the same instants for every "
         "run of a scene; each figure is the maximum over the scene's bodies. Orientation: "
         "geodesic angle 2 atan2(|vec(q_ref* q)|, |w(q_ref* q)|). omega, L: |x - x_ref| / "
         "|x_ref| in world axes. Drifts: max |E - E0| / |E0| and max ||L| - |L0|| / |L0|. "
         "Runs that blew up have no error figures; the time of the blow-up is given.\n\n"
      << "All figures are in `results.csv`, one row per run, columns: ";
  for (std::size_t i = 0; i < results_columns().size(); ++i) {
    out << (i ? ", " : "") << "`" << results_columns()[i] << "`";
  }
  out << " (times in s, errors in rad or relative, empty when the run blew up). "
         "`accepted_steps`, `rejected_steps` and `evaluations` are summed over the scene's "
         "bodies: one right-hand-side evaluation is one evaluation of the forces and the "
         "rotational rate at one state (engine/PHYSICS.md §5), counted as if every body had "
         "force terms; a fixed-step integrator makes its catalog figure per step (rk4 4, "
         "splitting 2, splitting4 6, free-rotor 2, the Euler variants 1; midpoint's 2 is the "
         "least its fixed-point solve takes), dopri counts its own (6 per attempt after the "
         "first, its last stage reused, and one more per step whose orientation it projects "
         "back onto the energy of a torque-free body). `seconds_median`, `seconds_min`, "
         "`seconds_max`: over "
         "the `repeats` timed runs.\n\n";
  for (std::size_t s = 0; s < outcome.scenes.size(); ++s) scene_section(out, outcome, s);
  write_text_file(file, out.str());
}

}  // namespace tumble::app
