// `tumble stability`: every case x integrator x dt, classified from the signed change of the
// invariants, written as a CSV, a markdown report and a heat map.
//
// Design: a case is run once per (integrator, dt) through engine::Simulation, which detects
// blow-ups; the runner watches the invariants that apply (energy of conservative bodies, |L|
// of torque-free ones, summed over bodies) every step and keeps their signed extremes, so
// growth (drift, blow-up) and loss (damping) are told apart. The error at the end is measured
// against the exact torque-free solution when every body is torque-free, else against one
// dopri run at engine::kReferenceTolerance per case (engine::ReferenceMotion).
#include "app/commands/stability_command.hpp"

#include "app/support/csv_writer.hpp"
#include "app/scene/option_lists.hpp"
#include "app/support/output_folder.hpp"
#include "app/support/printf_number.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <ostream>
#include <sstream>

#include <CLI/CLI.hpp>

#include "app/commands/exit_status.hpp"

#include "app/scene/scene.hpp"
#include "app/commands/simulate_command.hpp"
#include "app/analysis/gnuplot.hpp"
#include "app/analysis/stability_plot.hpp"
#include "app/analysis/stability_suite.hpp"
#include "engine/input_error.hpp"
#include "engine/integrators.hpp"
#include "engine/reference_motion.hpp"
#include "engine/simulation.hpp"

namespace tumble::app {
namespace {

using engine::InputError;
namespace fs = std::filesystem;


/// Splits a comma-separated option value; empty items are errors naming the option.
std::vector<engine::IntegratorInfo> parse_integrators(const std::optional<std::string>& text) {
  if (!text) return engine::integrator_catalog();
  std::vector<engine::IntegratorInfo> chosen;
  for (const engine::IntegratorInfo* info : parse_integrator_list(*text, "--integrators")) {
    chosen.push_back(*info);
  }
  return chosen;
}

/// The cases to run: the suite's (filtered by --cases), then the scene files.
std::vector<StabilityCase> gather_cases(const StabilityOptions& options, std::string& suite_name) {
  std::optional<std::vector<double>> dts;
  if (options.dts) dts = parse_positive_list(*options.dts, "--dts");
  std::vector<StabilityCase> cases;
  const bool use_suite = options.suite || options.cases || options.scenes.empty();
  if (use_suite) {
    StabilitySuite suite = stability_suite(options.suite.value_or("standard"));
    suite_name = suite.name;
    if (options.cases) {
      for (const std::string& name : split_option_list(*options.cases, "--cases")) {
        const auto found = std::find_if(suite.cases.begin(), suite.cases.end(),
                                         [&](const StabilityCase& c) { return c.name == name; });
        if (found == suite.cases.end()) {
          std::string names;
          for (const StabilityCase& c : suite.cases) names += (names.empty() ? "" : ", ") + c.name;
          throw InputError("--cases: no case '" + name + "' in suite '" + suite.name +
                           "'; expected one of: " + names);
        }
        cases.push_back(*found);
      }
    } else {
      cases = std::move(suite.cases);
    }
  }
  for (const fs::path& scene : options.scenes) cases.push_back(scene_case(scene, dts));
  return cases;
}

/// Energy of the conservative bodies and |L| of the torque-free ones, each summed.
engine::Invariants invariants(const std::vector<engine::BodyModel>& bodies,
                              const std::vector<engine::BodyState>& states) {
  return engine::total_invariants(bodies, states, engine::InvariantSum::kWhereConserved);
}

/// The reference states at the end of a case, and what they come from.
struct Reference {
  std::string kind = "none";
  std::vector<engine::BodyState> states;
};

/// The case's engine::ReferenceMotion at its end (dopri with a hundred output steps); "none"
/// when that run fails.
Reference reference_for(const StabilityCase& c) {
  const engine::ReferenceMotion motion(c.bodies, c.initial);
  try {
    return {motion.label(), motion.sample(c.duration / 100.0, c.duration).back()};
  } catch (const InputError&) {
    return {};
  }
}

/// One run of the sweep.
struct RunRecord {
  std::string case_name;
  std::string integrator;
  double dt = 0.0;
  double rate_dt = 0.0;
  double duration = 0.0;
  std::size_t steps = 0;
  std::size_t total_steps = 0;
  StabilityOutcome outcome = StabilityOutcome::kSkipped;
  InvariantChanges changes;
  std::optional<double> blowup_time;
  std::string blowup_reason;
  std::optional<double> orientation_error;  ///< rad
  std::optional<double> position_error;     ///< m
  std::string reference;
  double wall_seconds = 0.0;
  std::string note;
};

/// Runs one (case, integrator, dt).
RunRecord run_one(const StabilityCase& c, const engine::IntegratorInfo& info, double dt,
                  const Reference& reference) {
  RunRecord record;
  record.case_name = c.name;
  record.integrator = info.name;
  record.dt = dt;
  record.rate_dt = c.rate > 0.0 ? c.rate * dt : dt;
  record.duration = c.duration;
  record.reference = reference.kind;
  if (!c.only_integrators.empty() &&
      std::find(c.only_integrators.begin(), c.only_integrators.end(), info.name) ==
          c.only_integrators.end()) {
    record.note = c.skip_note;
    return record;
  }
  engine::SimulationSettings settings;
  settings.integrator = info.kind;
  settings.dt = dt;
  settings.duration = c.duration;
  settings.tolerance = c.tolerance;
  settings.blowup_factor = c.blowup_factor;
  std::optional<engine::Simulation> built;
  try {
    built.emplace(c.bodies, c.initial, settings);
  } catch (const InputError& error) {  // the exact solution on a forced case
    record.note = error.what();
    return record;
  }
  engine::Simulation& simulation = *built;
  record.total_steps = simulation.total_steps();

  // Step, keeping the signed extremes of the invariants.
  InvariantChanges& ch = record.changes;
  for (const engine::BodyModel& body : c.bodies) {
    ch.energy_applies = ch.energy_applies || body.conservative();
    ch.momentum_applies = ch.momentum_applies || body.torque_free();
  }
  const engine::Invariants start = invariants(simulation.bodies(), simulation.states());
  const double energy_scale =
      c.energy_scale ? *c.energy_scale : (start.energy != 0.0 ? std::abs(start.energy) : 1.0);
  const std::size_t late_from = record.total_steps - record.total_steps / 4;
  ch.energy_late_max = ch.momentum_late_max = -std::numeric_limits<double>::infinity();
  ch.energy_late_min = ch.momentum_late_min = std::numeric_limits<double>::infinity();
  const double momentum_scale = start.momentum != 0.0 ? start.momentum : 1.0;
  const auto begin = std::chrono::steady_clock::now();
  while (simulation.step()) {
    const engine::Invariants now = invariants(simulation.bodies(), simulation.states());
    const double de = (now.energy - start.energy) / energy_scale;
    const double dl = (now.momentum - start.momentum) / momentum_scale;
    ch.energy_final = de;
    ch.momentum_final = dl;
    ch.energy_max_gain = std::max(ch.energy_max_gain, de);
    ch.energy_max_loss = std::max(ch.energy_max_loss, -de);
    ch.momentum_max_gain = std::max(ch.momentum_max_gain, dl);
    ch.momentum_max_loss = std::max(ch.momentum_max_loss, -dl);
    if (simulation.steps() >= late_from) {
      ch.energy_late_max = std::max(ch.energy_late_max, de);
      ch.momentum_late_max = std::max(ch.momentum_late_max, dl);
      ch.energy_late_min = std::min(ch.energy_late_min, de);
      ch.momentum_late_min = std::min(ch.momentum_late_min, dl);
    }
  }
  record.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  record.steps = simulation.steps();
  if (!ch.energy_applies) {
    ch.energy_final = ch.energy_max_gain = ch.energy_max_loss = ch.energy_late_max = ch.energy_late_min = 0.0;
  }
  if (!ch.momentum_applies) {
    ch.momentum_final = ch.momentum_max_gain = ch.momentum_max_loss = ch.momentum_late_max = ch.momentum_late_min = 0.0;
  }

  // Blow-up, or the error at the end against the reference.
  if (const auto& blow_up = simulation.blow_up()) {
    record.blowup_time = blow_up->time;
    record.blowup_reason = "step " + std::to_string(blow_up->step) + ": " + blow_up->reason;
  } else if (!reference.states.empty()) {
    double orientation = 0.0, position = 0.0;
    for (std::size_t i = 0; i < c.bodies.size(); ++i) {
      const engine::BodyState& s = simulation.states()[i];
      orientation = std::max(orientation, engine::orientation_angle(reference.states[i].orientation,
                                                                    s.orientation));
      position = std::max(position, (reference.states[i].position - s.position).norm());
    }
    record.orientation_error = orientation;
    record.position_error = position;
  }
  record.outcome = classify(simulation.blow_up().has_value(), ch, kStabilityDriftThreshold);
  return record;
}

// ---------------------------------------------------------------------------------------------
// Outputs.

std::string csv_field(const std::string& text) {
  std::string out;
  append_csv_field(out, text);
  return out;
}

std::string optional_number(const std::optional<double>& value) {
  return value ? printf_number(*value, "%.6e") : std::string();
}

constexpr const char* kCsvHeader =
    "suite,case,integrator,dt,rate_label,rate_dt,duration,steps,total_steps,outcome,"
    "blowup_time,blowup_reason,energy_change_final,energy_max_gain,energy_max_loss,"
    "momentum_change_final,momentum_max_gain,momentum_max_loss,orientation_error,"
    "position_error,reference,wall_seconds,note";

std::string csv_text(const std::string& suite, const std::vector<StabilityCase>& cases,
                     const std::vector<RunRecord>& runs) {
  std::ostringstream out;
  out << kCsvHeader << "\n";
  for (const RunRecord& r : runs) {
    const auto found = std::find_if(cases.begin(), cases.end(),
                                    [&](const StabilityCase& c) { return c.name == r.case_name; });
    const bool ran = r.outcome != StabilityOutcome::kSkipped;
    const auto invariant = [&](bool applies, double value) {
      return ran && applies ? printf_number(value, "%.6e") : std::string();
    };
    const InvariantChanges& ch = r.changes;
    out << csv_field(suite) << "," << csv_field(r.case_name) << "," << r.integrator << ","
        << printf_number(r.dt, "%.9g") << "," << csv_field(found->rate_label) << ","
        << printf_number(r.rate_dt, "%.6g") << "," << printf_number(r.duration, "%.9g") << ","
        << r.steps << "," << r.total_steps << "," << outcome_name(r.outcome) << ","
        << optional_number(r.blowup_time) << "," << csv_field(r.blowup_reason) << ","
        << invariant(ch.energy_applies, ch.energy_final) << ","
        << invariant(ch.energy_applies, ch.energy_max_gain) << ","
        << invariant(ch.energy_applies, ch.energy_max_loss) << ","
        << invariant(ch.momentum_applies, ch.momentum_final) << ","
        << invariant(ch.momentum_applies, ch.momentum_max_gain) << ","
        << invariant(ch.momentum_applies, ch.momentum_max_loss) << ","
        << optional_number(r.orientation_error) << "," << optional_number(r.position_error) << ","
        << csv_field(ran ? r.reference : "") << "," << printf_number(r.wall_seconds, "%.4g") << ","
        << csv_field(r.note) << "\n";
  }
  return out.str();
}

/// The largest signed excursion of the applicable invariants over the run (+gain or -loss).
double decisive_change(const InvariantChanges& ch) {
  double best = 0.0;
  for (const double change :
       {ch.energy_applies ? ch.energy_max_gain : 0.0, ch.energy_applies ? -ch.energy_max_loss : 0.0,
        ch.momentum_applies ? ch.momentum_max_gain : 0.0,
        ch.momentum_applies ? -ch.momentum_max_loss : 0.0}) {
    if (std::abs(change) > std::abs(best)) best = change;
  }
  return best;
}

std::string cell_text(const RunRecord& r) {
  switch (r.outcome) {
    case StabilityOutcome::kBlewUp:
      return "blew up (t = " + printf_number(*r.blowup_time, "%.4g") + " s)";
    case StabilityOutcome::kDamped:
    case StabilityOutcome::kDrifting:
      return std::string(outcome_name(r.outcome)) + " (" +
             printf_number(decisive_change(r.changes), "%+.1e") + ")";
    default:
      return outcome_name(r.outcome);
  }
}

const char* kRules =
    "Each run watches the invariants that apply to its case: the energy of conservative bodies "
    "and |L| of torque-free bodies (each summed over the bodies), as signed changes relative to "
    "their initial values (absolute when the initial value is 0; a case may name another energy "
    "scale, see its note): gain = max (X - X0) / |X0|, "
    "loss = max (X0 - X) / |X0| over every step, final = (X_end - X0) / |X0|. With threshold "
    "tau = 1e-3, in this order:\n\n"
    "1. **blew up**: the simulation stopped the run (non-finite state, energy drift beyond "
    "(F - 1) |E0| or |L| growth beyond F, F the blow-up factor, 10 unless the case says), "
    "reported with the time;\n"
    "2. **unchecked**: neither energy nor |L| is an invariant of the case (torques, damping);\n"
    "3. **stable**: gain <= tau and loss <= tau for every applicable invariant;\n"
    "4. **damped**: some invariant stays below X0 by more than tau through the whole last "
    "quarter of the run (late max < -tau), swinging there by less than half that loss (late "
    "max - late min < |late max| / 2: a persistent loss, not a wide bounded swing below X0 as "
    "Verlet's on a spring), and no invariant ever gained more than tau;\n"
    "5. **drifting**: otherwise: bounded (no blow-up), but a gain beyond tau or swings beyond "
    "it.\n\n"
    "Cells of drifting and damped runs show the largest signed excursion over the run (+gain or "
    "-loss). Error: orientation angle (rad) and position (m) at the end against the exact "
    "torque-free solution when every body is torque-free, else against one dopri run at "
    "tolerance 1e-13 (`reference` column of the CSV; none when that run failed). "
    "`skipped` runs were not made (the reason is in the CSV's `note`).\n";

std::string markdown_text(const std::string& suite, const std::vector<StabilityCase>& cases,
                          const std::vector<engine::IntegratorInfo>& integrators,
                          const std::vector<RunRecord>& runs) {
  std::ostringstream out;
  out << "# tumble stability" << (suite.empty() ? "" : ": suite `" + suite + "`") << "\n\n";
  out << "## Classification rules\n\n" << kRules << "\n";
  std::size_t index = 0;
  for (const StabilityCase& c : cases) {
    out << "## Case `" << c.name << "`\n\n" << c.description << ". Duration "
        << printf_number(c.duration) << " s";
    if (c.rate > 0.0) out << "; columns are " << c.rate_label << " (rate " << printf_number(c.rate)
                          << " 1/s)";
    else out << "; columns are dt in s";
    out << ".\n\n| integrator |";
    for (const double dt : c.dts) {
      out << " " << printf_number(c.rate > 0.0 ? c.rate * dt : dt, "%.4g") << " |";
    }
    out << "\n|---|";
    for (std::size_t k = 0; k < c.dts.size(); ++k) out << "---|";
    out << "\n";
    std::string reference = "none";
    for (const engine::IntegratorInfo& info : integrators) {
      out << "| " << info.name << " |";
      for (std::size_t k = 0; k < c.dts.size(); ++k) {
        const RunRecord& r = runs[index++];
        if (r.outcome != StabilityOutcome::kSkipped) reference = r.reference;
        out << " " << cell_text(r) << " |";
      }
      out << "\n";
    }
    out << "\nError reference: " << reference << ".";
    if (!c.only_integrators.empty()) out << " Skipped: every integrator but the cheap ones (" << c.skip_note << ").";
    if (c.note) out << " Note: " << *c.note << ".";
    out << "\n\n";
  }
  out << "Heat map: `stability.png`, `stability.svg`. Every run: `stability.csv`.\n";
  return out.str();
}

void write_file(const fs::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary);
  out << text;
  out.close();
  if (!out) throw InputError("cannot write " + file.string());
}

/// A stability output: stability.md under its title (and the suite), beside stability.csv.
const OutputFolderKind kStabilityOutput{"stability", "stability.md", "# tumble stability",
                                        "stability.csv"};

int list_suites(std::ostream& out) {
  for (const SuiteListing& suite : stability_suite_listing()) {
    out << suite.name << "  " << suite.description << "\n";
  }
  return 0;
}

int stability(const StabilityOptions& options, std::ostream& out, std::ostream& err) {
  // Options, cases and the output folder are checked before any run.
  if (!options.output) throw InputError("-o DIR is required (or --list-suites)");
  const std::vector<engine::IntegratorInfo> integrators = parse_integrators(options.integrators);
  std::string suite;
  const std::vector<StabilityCase> cases = gather_cases(options, suite);
  if (!gnuplot_available()) throw InputError("gnuplot is not installed (needed for the heat map)");
  const fs::path output = *options.output;
  const fs::path temporary = start_output_folder(output, kStabilityOutput);
  try {
    // The sweep, case by case.
    std::vector<RunRecord> runs;
    for (std::size_t k = 0; k < cases.size(); ++k) {
      const StabilityCase& c = cases[k];
      err << "tumble stability: [" << k + 1 << "/" << cases.size() << "] " << c.name << ": "
          << integrators.size() * c.dts.size() << " runs\n" << std::flush;
      const Reference reference = reference_for(c);
      for (const engine::IntegratorInfo& info : integrators) {
        for (const double dt : c.dts) runs.push_back(run_one(c, info, dt, reference));
      }
    }

    // The outputs, then the folder into place.
    write_file(temporary / "stability.csv", csv_text(suite, cases, runs));
    write_file(temporary / "stability.md", markdown_text(suite, cases, integrators, runs));
    std::vector<HeatMapPanel> panels;
    std::size_t index = 0;
    for (const StabilityCase& c : cases) {
      HeatMapPanel panel;
      panel.title = c.name;
      panel.x_label = c.rate > 0.0 ? c.rate_label : "dt (s)";
      for (const double dt : c.dts) {
        panel.columns.push_back(printf_number(c.rate > 0.0 ? c.rate * dt : dt, "%.4g"));
      }
      for (const engine::IntegratorInfo& info : integrators) {
        panel.rows.push_back(info.name);
        std::vector<StabilityOutcome> row;
        for (std::size_t d = 0; d < c.dts.size(); ++d) row.push_back(runs[index++].outcome);
        panel.cells.push_back(row);
      }
      panels.push_back(panel);
    }
    draw_heat_map(panels, temporary / "stability.png", temporary / "stability.svg");
    finish_output_folder(temporary, output);

    // Summary on stdout.
    std::size_t counts[6] = {};
    for (const RunRecord& r : runs) ++counts[static_cast<int>(r.outcome)];
    out << "tumble stability: " << runs.size() << " runs over " << cases.size() << " cases: ";
    for (int o = 0; o < 6; ++o) {
      out << (o ? ", " : "") << counts[o] << " " << outcome_name(static_cast<StabilityOutcome>(o));
    }
    out << "\n  wrote " << (output / "stability.csv").string() << ", stability.md, stability.png, "
        << "stability.svg\n";
  } catch (...) {
    std::error_code ignored;
    fs::remove_all(temporary, ignored);
    throw;
  }
  return 0;
}

}  // namespace

CLI::App& add_stability_command(CLI::App& cli, StabilityOptions& options) {
  CLI::App& command = *cli.add_subcommand(
      "stability", "Stiff and extreme cases over every integrator and a dt sweep: CSV, "
                   "markdown matrices and a heat map");
  command.add_option_function<std::string>(
      "--suite", [&](const std::string& value) { options.suite = value; },
      "Built-in suite (default standard; see --list-suites)");
  command.add_option_function<std::string>(
      "--integrators", [&](const std::string& value) { options.integrators = value; },
      "Comma-separated integrators (default: all)");
  command.add_option_function<std::string>(
      "--dts", [&](const std::string& value) { options.dts = value; },
      "Comma-separated time steps in s for the SCENE cases (default: the scene's dt x 1, 2, 4, 8)");
  command.add_option_function<std::string>(
      "--cases", [&](const std::string& value) { options.cases = value; },
      "Comma-separated built-in cases of the suite (default: all)");
  command.add_option_function<std::vector<std::string>>(
      "SCENE", [&](const std::vector<std::string>& values) {
        for (const std::string& value : values) options.scenes.emplace_back(value);
      },
      "Scene files added as cases (alone: only they run, unless --suite or --cases is given)");
  command.add_option_function<std::string>(
      "-o,--output", [&](const std::string& value) { options.output = value; },
      "Output folder DIR (written atomically: .DIR.tmp-PID renamed at the end)");
  command.add_flag("--list-suites", options.list_suites, "List the built-in suites, then exit");
  return command;
}

int run_stability(const StabilityOptions& options, std::ostream& out, std::ostream& err) {
  return run_guarded("stability", err, [&] {
    return options.list_suites ? list_suites(out) : stability(options, out, err);
  });
}

}  // namespace tumble::app
