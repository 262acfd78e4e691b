// The outputs of `tumble stability`: CSV rows, markdown matrices and heat map panels, all read
// from the runs in the sweep's order (case, integrator, dt).
#include "app/analysis/stability_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <sstream>

#include "app/support/csv_writer.hpp"
#include "app/support/printf_number.hpp"

namespace tumble::app {
namespace {

constexpr const char* kCsvHeader =
    "suite,case,integrator,dt,rate_label,rate_dt,duration,steps,total_steps,outcome,"
    "blowup_time,blowup_reason,energy_change_final,energy_max_gain,energy_max_loss,"
    "momentum_change_final,momentum_max_gain,momentum_max_loss,orientation_error,"
    "position_error,momentum_error,motion_range,reference_instants,reference,wall_seconds,note";

std::string optional_number(const std::optional<double>& value) {
  return value ? printf_number(*value, "%.6e") : std::string();
}

/// The fields of run `r` of case `c`, in the order of kCsvHeader.
std::vector<std::string> csv_fields(const std::string& suite, const StabilityCase& c,
                                    const StabilityRun& r) {
  const bool ran = r.outcome != StabilityOutcome::kSkipped;
  const auto invariant = [&](bool applies, double value) {
    return ran && applies ? printf_number(value, "%.6e") : std::string();
  };
  const InvariantChanges& ch = r.changes;
  return {suite,
          r.case_name,
          r.integrator,
          printf_number(r.dt, "%.9g"),
          c.rate_label,
          printf_number(r.rate_dt, "%.6g"),
          printf_number(r.duration, "%.9g"),
          std::to_string(r.steps),
          std::to_string(r.total_steps),
          outcome_name(r.outcome),
          optional_number(r.blowup_time),
          r.blowup_reason,
          invariant(ch.energy_applies, ch.energy_final),
          invariant(ch.energy_applies, ch.energy_max_gain),
          invariant(ch.energy_applies, ch.energy_max_loss),
          invariant(ch.momentum_applies, ch.momentum_final),
          invariant(ch.momentum_applies, ch.momentum_max_gain),
          invariant(ch.momentum_applies, ch.momentum_max_loss),
          optional_number(r.orientation_error),
          optional_number(r.position_error),
          optional_number(r.momentum_error),
          r.position_error ? printf_number(r.motion_range, "%.6e") : std::string(),
          ran ? std::to_string(r.reference_instants) : "",
          ran ? r.reference : "",
          printf_number(r.wall_seconds, "%.4g"),
          r.note};
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

/// Whether positions are worth an error column: some free body is pushed (a spring, gravity) or
/// moves (a free body at rest or coasting is moved exactly by every integrator).
bool has_positions(const StabilityCase& c) {
  for (std::size_t i = 0; i < c.bodies.size(); ++i) {
    if (c.bodies[i].pivoted) continue;
    if (!c.bodies[i].forces.empty() || c.initial[i].velocity != Eigen::Vector3d::Zero()) {
      return true;
    }
  }
  return false;
}

/// The class, the largest signed excursion for drifting, damped and wrong runs, and the errors
/// against the reference: "wrong (-4.1e-02), 2.3e-03 rad" or "stable, 1.0e-07 rad, 2.0e-06 m".
std::string cell_text(const StabilityCase& c, const StabilityRun& r) {
  std::string text;
  switch (r.outcome) {
    case StabilityOutcome::kBlewUp:
      return "blew up (t = " + printf_number(*r.blowup_time, "%.4g") + " s)";
    case StabilityOutcome::kSkipped:
    case StabilityOutcome::kUnchecked:
      return outcome_name(r.outcome);
    case StabilityOutcome::kDamped:
    case StabilityOutcome::kDrifting:
    case StabilityOutcome::kWrong:
      text = std::string(outcome_name(r.outcome));
      if (const double change = decisive_change(r.changes); change != 0.0) {
        text += " (" + printf_number(change, "%+.1e") + ")";
      }
      break;
    case StabilityOutcome::kStable:
      text = outcome_name(r.outcome);
      break;
  }
  if (r.orientation_error) text += ", " + printf_number(*r.orientation_error, "%.1e") + " rad";
  if (r.position_error && has_positions(c)) {
    text += ", " + printf_number(*r.position_error, "%.1e") + " m";
  }
  return text;
}

/// The heading of the matrix column of step `dt`: rate x dt, or dt in seconds.
std::string column_label(const StabilityCase& c, double dt) {
  return printf_number(c.rate > 0.0 ? c.rate * dt : dt, "%.4g");
}

const char* kRules =
    "Each run watches the invariants of its case, as signed changes relative to a scale that "
    "depends neither on the origin nor on a potential's zero (engine/PHYSICS.md §6): for the "
    "energy, the kinetic energy plus each potential's available swing, from the initial state "
    "(a case may name another, see its note); for |L|, |L0|. When every body keeps the "
    "invariant (energy: conservative; |L|: torque-free) it is compared with its initial value "
    "after every step: gain = max (X - X0) / S, loss = max (X0 - X) / S, final = "
    "(X_end - X0) / S. When some body is forced (torques, damping), the sums over every body "
    "are compared with the reference's at the instants the run shares with it (X0 replaced by "
    "X_ref(t)). With threshold tau = 1e-3, in this order:\n\n"
    "1. **blew up**: the simulation stopped the run (non-finite state, energy drift beyond "
    "(F - 1) times the energy scale, or |L| growth beyond F, F the blow-up factor, 10 unless "
    "the case says), reported with the time;\n"
    "2. **wrong**: bounded, but against the reference the orientation error exceeds 0.1 rad, "
    "the world L vector is off by more than 1% of |L_ref|, or a free body's position by more "
    "than 10% of the reference's range of motion (the farthest a free body gets from its "
    "start), or the energy is off by more than 1% of the scale (gain or loss > 1e-2) at some "
    "watched instant;\n"
    "3. **unchecked**: nothing to check against (no invariant and no reference);\n"
    "4. **stable**: gain <= tau and loss <= tau for every applicable invariant;\n"
    "5. **damped**: some invariant stays below X0 by more than tau through the whole last "
    "quarter of the run (late max < -tau), swinging there by less than half that loss (late "
    "max - late min < |late max| / 2: a persistent loss, not a wide bounded swing below X0 as "
    "Verlet's on a spring), and no invariant ever gained more than tau;\n"
    "6. **drifting**: otherwise: bounded, but a gain beyond tau or swings beyond it.\n\n"
    "Cells of drifting, damped and wrong runs show the largest signed excursion (+gain or "
    "-loss, in units of the scale). Every run that did not blow up shows its error against the "
    "reference: the orientation angle (rad) and, for cases whose free bodies are pushed or "
    "move, the position (m), each the largest over the bodies and over the instants the run "
    "shares with the reference's samples (every hundredth of the run where the steps land on "
    "them, always the end; CSV `reference_instants`). The reference is the exact solution "
    "when every body is torque-free or a heavy symmetric top, else one dopri run at tolerance "
    "1e-13 "
    "(`reference` column of the CSV; none when that run failed). "
    "`skipped` runs were not made (the reason is in the CSV's `note`).\n";

/// Case `c`'s section of the report: its description, its matrix (from `runs[index]` on,
/// advancing `index` past them) and the notes under it.
void write_case_section(std::ostream& out, const StabilityCase& c,
                        const std::vector<engine::IntegratorInfo>& integrators,
                        const std::vector<StabilityRun>& runs, std::size_t& index) {
  // The case and what its columns show.
  out << "## Case `" << c.name << "`\n\n"
      << c.description << ". Duration " << printf_number(c.duration) << " s";
  if (c.rate > 0.0)
    out << "; columns are " << c.rate_label << " (rate " << printf_number(c.rate) << " 1/s)";
  else
    out << "; columns are dt in s";

  // The matrix: one row per integrator, one column per dt.
  out << ".\n\n| integrator |";
  for (const double dt : c.dts) out << " " << column_label(c, dt) << " |";
  out << "\n|---|";
  for (std::size_t k = 0; k < c.dts.size(); ++k) out << "---|";
  out << "\n";
  std::string reference = "none";
  for (const engine::IntegratorInfo& info : integrators) {
    out << "| " << info.name << " |";
    for (std::size_t k = 0; k < c.dts.size(); ++k) {
      const StabilityRun& r = runs[index++];
      if (r.outcome != StabilityOutcome::kSkipped) reference = r.reference;
      out << " " << cell_text(c, r) << " |";
    }
    out << "\n";
  }

  // The notes under it.
  out << "\nError reference: " << reference << ".";
  if (!c.only_integrators.empty()) {
    out << " Skipped: every integrator but the cheap ones (" << c.skip_note << ").";
  }
  if (c.note) out << " Note: " << *c.note << ".";
  out << "\n\n";
}

}  // namespace

std::string stability_csv(const std::string& suite, const std::vector<StabilityCase>& cases,
                          const std::vector<StabilityRun>& runs) {
  std::string out = std::string(kCsvHeader) + "\n";
  for (const StabilityRun& r : runs) {
    const auto found = std::find_if(cases.begin(), cases.end(),
                                    [&](const StabilityCase& c) { return c.name == r.case_name; });
    const std::vector<std::string> fields = csv_fields(suite, *found, r);
    for (std::size_t i = 0; i < fields.size(); ++i) {
      if (i > 0) out += ',';
      append_csv_field(out, fields[i]);
    }
    out += '\n';
  }
  return out;
}

std::string stability_markdown(const std::string& suite, const std::vector<StabilityCase>& cases,
                               const std::vector<engine::IntegratorInfo>& integrators,
                               const std::vector<StabilityRun>& runs) {
  std::ostringstream out;
  out << "# tumble stability" << (suite.empty() ? "" : ": suite `" + suite + "`") << "\n\n";
  out << "## Classification rules\n\n" << kRules << "\n";
  std::size_t index = 0;
  for (const StabilityCase& c : cases) write_case_section(out, c, integrators, runs, index);
  out << "Heat map: `stability.png`, `stability.svg`. Every run: `stability.csv`.\n";
  return out.str();
}

std::vector<HeatMapPanel> stability_heat_map(const std::vector<StabilityCase>& cases,
                                             const std::vector<engine::IntegratorInfo>& integrators,
                                             const std::vector<StabilityRun>& runs) {
  std::vector<HeatMapPanel> panels;
  std::size_t index = 0;
  for (const StabilityCase& c : cases) {
    HeatMapPanel panel;
    panel.title = c.name;
    panel.x_label = c.rate > 0.0 ? c.rate_label : "dt (s)";
    for (const double dt : c.dts) panel.columns.push_back(column_label(c, dt));
    for (const engine::IntegratorInfo& info : integrators) {
      panel.rows.push_back(info.name);
      std::vector<StabilityOutcome> row;
      for (std::size_t d = 0; d < c.dts.size(); ++d) row.push_back(runs[index++].outcome);
      panel.cells.push_back(row);
    }
    panels.push_back(panel);
  }
  return panels;
}

}  // namespace tumble::app
