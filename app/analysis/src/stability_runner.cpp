// One run of `tumble stability`: the invariants are watched every step and their signed
// extremes kept, so growth (drift, blow-up) and loss (damping) are told apart; the last quarter
// of the steps is kept apart too, to tell a persistent loss from a wide bounded swing.
#include "app/analysis/stability_runner.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "engine/input_error.hpp"
#include "engine/reference_motion.hpp"
#include "engine/simulation.hpp"

namespace tumble::app {
namespace {

/// Energy of the conservative bodies and |L| of the torque-free ones, each summed.
engine::Invariants invariants(const engine::Simulation& simulation) {
  return engine::total_invariants(simulation.bodies(), simulation.states(),
                                  engine::InvariantSum::kWhereConserved);
}

/// Whether the case lets `integrator` run (it may name the only ones that do).
bool case_runs(const StabilityCase& c, const std::string& integrator) {
  return c.only_integrators.empty() ||
         std::find(c.only_integrators.begin(), c.only_integrators.end(), integrator) !=
             c.only_integrators.end();
}

/// The run before it is made: what it is, skipped until it has run.
StabilityRun planned_run(const StabilityCase& c, const engine::IntegratorInfo& info, double dt,
                         const StabilityReference& reference) {
  StabilityRun run;
  run.case_name = c.name;
  run.integrator = info.name;
  run.dt = dt;
  run.rate_dt = c.rate > 0.0 ? c.rate * dt : dt;
  run.duration = c.duration;
  run.reference = reference.kind;
  return run;
}

engine::SimulationSettings sweep_settings(const StabilityCase& c, engine::IntegratorKind kind,
                                          double dt) {
  engine::SimulationSettings settings;
  settings.integrator = kind;
  settings.dt = dt;
  settings.duration = c.duration;
  settings.tolerance = c.tolerance;
  settings.blowup_factor = c.blowup_factor;
  return settings;
}

/// Keeps one step's relative changes `de` (energy) and `dl` (|L|) among the extremes; `late`
/// when the step is in the last quarter of the run.
void keep_extremes(InvariantChanges& ch, double de, double dl, bool late) {
  ch.energy_final = de;
  ch.momentum_final = dl;
  ch.energy_max_gain = std::max(ch.energy_max_gain, de);
  ch.energy_max_loss = std::max(ch.energy_max_loss, -de);
  ch.momentum_max_gain = std::max(ch.momentum_max_gain, dl);
  ch.momentum_max_loss = std::max(ch.momentum_max_loss, -dl);
  if (late) {
    ch.energy_late_max = std::max(ch.energy_late_max, de);
    ch.momentum_late_max = std::max(ch.momentum_late_max, dl);
    ch.energy_late_min = std::min(ch.energy_late_min, de);
    ch.momentum_late_min = std::min(ch.momentum_late_min, dl);
  }
}

/// Zeroes the changes of the invariants that do not apply to the case.
void clear_inapplicable(InvariantChanges& ch) {
  if (!ch.energy_applies) {
    ch.energy_final = ch.energy_max_gain = ch.energy_max_loss = ch.energy_late_max =
        ch.energy_late_min = 0.0;
  }
  if (!ch.momentum_applies) {
    ch.momentum_final = ch.momentum_max_gain = ch.momentum_max_loss = ch.momentum_late_max =
        ch.momentum_late_min = 0.0;
  }
}

/// Steps `simulation` to its end or its blow-up (or until `stop` says so: run.stopped), keeping
/// the signed extremes of the invariants in `run.changes` and timing the loop.
void step_watching_invariants(const StabilityCase& c, engine::Simulation& simulation,
                              StabilityRun& run, const std::function<bool()>& stop) {
  // The invariants that apply, their start values and scales.
  InvariantChanges& ch = run.changes;
  for (const engine::BodyModel& body : c.bodies) {
    ch.energy_applies = ch.energy_applies || body.conservative();
    ch.momentum_applies = ch.momentum_applies || body.torque_free();
  }
  const engine::Invariants start = invariants(simulation);
  const double energy_scale =
      c.energy_scale ? *c.energy_scale : (start.energy != 0.0 ? std::abs(start.energy) : 1.0);
  const std::size_t late_from = run.total_steps - run.total_steps / 4;
  ch.energy_late_max = ch.momentum_late_max = -std::numeric_limits<double>::infinity();
  ch.energy_late_min = ch.momentum_late_min = std::numeric_limits<double>::infinity();
  const double momentum_scale = start.momentum != 0.0 ? start.momentum : 1.0;

  // Step, keeping the signed extremes.
  const auto begin = std::chrono::steady_clock::now();
  while (simulation.step()) {
    if (stop && simulation.steps() % kStopCheckSteps == 0 && stop()) {
      run.stopped = true;
      break;
    }
    const engine::Invariants now = invariants(simulation);
    keep_extremes(ch, (now.energy - start.energy) / energy_scale,
                  (now.momentum - start.momentum) / momentum_scale,
                  simulation.steps() >= late_from);
  }
  run.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  run.steps = simulation.steps();
  clear_inapplicable(ch);
}

/// The blow-up, or the largest orientation and position errors at the end against the
/// reference (when it has states).
void measure_end(const engine::Simulation& simulation, const StabilityReference& reference,
                 StabilityRun& run) {
  if (const auto& blow_up = simulation.blow_up()) {
    run.blowup_time = blow_up->time;
    run.blowup_reason = "step " + std::to_string(blow_up->step) + ": " + blow_up->reason;
  } else if (!reference.states.empty()) {
    double orientation = 0.0, position = 0.0;
    for (std::size_t i = 0; i < simulation.states().size(); ++i) {
      const engine::BodyState& s = simulation.states()[i];
      orientation = std::max(
          orientation, engine::orientation_angle(reference.states[i].orientation, s.orientation));
      position = std::max(position, (reference.states[i].position - s.position).norm());
    }
    run.orientation_error = orientation;
    run.position_error = position;
  }
}

}  // namespace

StabilityReference stability_reference(const StabilityCase& c) {
  const engine::ReferenceMotion motion(c.bodies, c.initial);
  try {
    return {motion.label(), motion.sample(c.duration / 100.0, c.duration).back()};
  } catch (const engine::InputError&) {
    return {};
  }
}

StabilityRun run_stability_case(const StabilityCase& c, const engine::IntegratorInfo& info,
                                double dt, const StabilityReference& reference,
                                const std::function<bool()>& stop) {
  StabilityRun run = planned_run(c, info, dt, reference);
  if (!case_runs(c, info.name)) {
    run.note = c.skip_note;
    return run;
  }
  std::optional<engine::Simulation> built;
  try {
    built.emplace(c.bodies, c.initial, sweep_settings(c, info.kind, dt));
  } catch (const engine::InputError& error) {  // the exact solution on a forced case
    run.note = error.what();
    return run;
  }
  engine::Simulation& simulation = *built;
  run.total_steps = simulation.total_steps();
  step_watching_invariants(c, simulation, run, stop);
  if (run.stopped) return run;
  measure_end(simulation, reference, run);
  run.outcome = classify(simulation.blow_up().has_value(), run.changes, kStabilityDriftThreshold);
  return run;
}

}  // namespace tumble::app
