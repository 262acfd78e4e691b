// One run of `tumble stability`: the invariants are watched every step (or, for a forced case,
// at the instants shared with the reference, against the reference's) and their signed extremes
// kept, so growth (drift, blow-up) and loss (damping) are told apart; the last quarter of the
// steps is kept apart too, to tell a persistent loss from a wide bounded swing. The errors
// against the reference are the largest over the shared instants.
#include "app/analysis/stability_runner.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "base/errors.hpp"
#include "engine/simulation/reference_motion.hpp"
#include "engine/simulation/simulation.hpp"

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
  settings.absolute_tolerance = c.absolute_tolerance;
  settings.blowup_factor = c.blowup_factor;
  return settings;
}

/// Keeps one relative change among the extremes of one invariant; `late` when the instant is
/// in the last quarter of the run.
struct Extremes {
  double& final;
  double& gain;
  double& loss;
  double& late_min;
  double& late_max;
  void keep(double change, bool late) const {
    final = change;
    gain = std::max(gain, change);
    loss = std::max(loss, -change);
    if (late) {
      late_min = std::min(late_min, change);
      late_max = std::max(late_max, change);
    }
  }
};

Extremes energy_extremes(InvariantChanges& ch) {
  return {ch.energy_final, ch.energy_max_gain, ch.energy_max_loss, ch.energy_late_min,
          ch.energy_late_max};
}
Extremes momentum_extremes(InvariantChanges& ch) {
  return {ch.momentum_final, ch.momentum_max_gain, ch.momentum_max_loss, ch.momentum_late_min,
          ch.momentum_late_max};
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

/// How a run is judged (engine/PHYSICS.md §7): whether each invariant is compared with its
/// start (every body keeps it) or with the reference at the shared instants (some body is
/// forced), and the scales the changes are divided by.
struct Watch {
  bool energy_vs_reference = false;
  bool momentum_vs_reference = false;
  engine::Invariants start;  ///< summed over the bodies that keep each invariant
  double energy_scale = 1.0;
  double momentum_scale = 1.0;
};

/// The origin-free energy scale (engine::energy_scale) and |L| summed over the bodies in
/// `states` at time `t`; only the conservative (torque-free) ones unless `all`.
engine::Invariants scales(const StabilityCase& c, const std::vector<engine::BodyState>& states,
                          double t, bool all) {
  engine::Invariants sum;
  for (std::size_t i = 0; i < c.bodies.size(); ++i) {
    if (all || c.bodies[i].conservative()) {
      sum.energy += engine::energy_scale(c.bodies[i], states[i], c.duration - t);
    }
    if (all || c.bodies[i].torque_free()) sum.momentum += states[i].angular_momentum.norm();
  }
  return sum;
}

Watch plan_watch(const StabilityCase& c, const engine::Simulation& simulation,
                 const StabilityReference& reference, InvariantChanges& ch) {
  bool all_conservative = true, all_torque_free = true, any_conservative = false,
       any_torque_free = false;
  for (const engine::BodyModel& body : c.bodies) {
    all_conservative = all_conservative && body.conservative();
    all_torque_free = all_torque_free && body.torque_free();
    any_conservative = any_conservative || body.conservative();
    any_torque_free = any_torque_free || body.torque_free();
  }
  const bool has_reference = !reference.samples.empty();
  Watch w;
  w.energy_vs_reference = !all_conservative && has_reference;
  w.momentum_vs_reference = !all_torque_free && has_reference;
  ch.energy_applies = any_conservative || w.energy_vs_reference;
  ch.momentum_applies = any_torque_free || w.momentum_vs_reference;
  w.start = invariants(simulation);

  // The scales: from the initial state, and for a forced case the largest along the reference
  // (its energy may grow under the forcing; the run's own values never enter, which would let a
  // blowing-up run scale its own error away).
  const engine::Invariants initial =
      scales(c, simulation.states(), 0.0, w.energy_vs_reference || w.momentum_vs_reference);
  double energy = initial.energy, momentum = initial.momentum;
  for (std::size_t j = 0; j < reference.samples.size(); ++j) {
    const double t = std::min(c.duration, static_cast<double>(j + 1) * reference.interval);
    const engine::Invariants along = scales(c, reference.samples[j], t, true);
    if (w.energy_vs_reference) energy = std::max(energy, along.energy);
    if (w.momentum_vs_reference) momentum = std::max(momentum, along.momentum);
  }
  w.energy_scale = c.energy_scale ? *c.energy_scale : (energy > 0.0 ? energy : 1.0);
  w.momentum_scale = momentum > 0.0 ? momentum : 1.0;
  return w;
}

/// The index of the reference sample at time `t`, when the run's step ends on one.
std::optional<std::size_t> shared_sample(const StabilityReference& reference, double t,
                                         double duration) {
  const std::size_t n = reference.samples.size();
  if (n == 0) return std::nullopt;
  const double slack = 1e-9 * reference.interval;
  if (std::abs(t - duration) <= slack) return n - 1;
  const double k = std::round(t / reference.interval);
  if (k < 1.0 || k >= static_cast<double>(n) || std::abs(t - k * reference.interval) > slack) {
    return std::nullopt;
  }
  return static_cast<std::size_t>(k) - 1;
}

/// At a shared instant: the errors of the states against sample `j`, and the invariants that
/// are compared with the reference's.
void compare_with_reference(const engine::Simulation& simulation,
                            const StabilityReference& reference, std::size_t j, const Watch& w,
                            bool late, StabilityRun& run) {
  const std::vector<engine::BodyState>& ref = reference.samples[j];
  double orientation = run.orientation_error.value_or(0.0);
  double position = run.position_error.value_or(0.0);
  double momentum = run.momentum_error.value_or(0.0);
  for (std::size_t i = 0; i < simulation.states().size(); ++i) {
    const engine::BodyState& s = simulation.states()[i];
    orientation =
        std::max(orientation, engine::orientation_angle(ref[i].orientation, s.orientation));
    position = std::max(position, (ref[i].position - s.position).norm());
    const double l_ref = ref[i].angular_momentum.norm();
    const double l_error = (s.angular_momentum - ref[i].angular_momentum).norm();
    momentum = std::max(momentum, l_ref > 0.0 ? l_error / l_ref : l_error);
  }
  run.orientation_error = orientation;
  run.position_error = position;
  run.momentum_error = momentum;
  ++run.reference_instants;
  if (!w.energy_vs_reference && !w.momentum_vs_reference) return;
  const engine::Invariants now = engine::total_invariants(simulation.bodies(), simulation.states(),
                                                          engine::InvariantSum::kAll);
  if (w.energy_vs_reference) {
    energy_extremes(run.changes)
        .keep((now.energy - reference.invariants[j].energy) / w.energy_scale, late);
  }
  if (w.momentum_vs_reference) {
    momentum_extremes(run.changes)
        .keep((now.momentum - reference.invariants[j].momentum) / w.momentum_scale, late);
  }
}

/// Steps `simulation` to its end or its blow-up (or until `stop` says so: run.stopped), keeping
/// the signed extremes of the invariants in `run.changes`, the errors at the instants shared
/// with the reference, and timing the loop.
void step_watching_invariants(const StabilityCase& c, engine::Simulation& simulation,
                              const StabilityReference& reference, StabilityRun& run,
                              const std::function<bool()>& stop) {
  InvariantChanges& ch = run.changes;
  const Watch w = plan_watch(c, simulation, reference, ch);
  const std::size_t late_from = run.total_steps - run.total_steps / 4;
  ch.energy_late_max = ch.momentum_late_max = -std::numeric_limits<double>::infinity();
  ch.energy_late_min = ch.momentum_late_min = std::numeric_limits<double>::infinity();

  // Step, keeping the signed extremes.
  const auto begin = std::chrono::steady_clock::now();
  while (simulation.step()) {
    if (stop && simulation.steps() % kStopCheckSteps == 0 && stop()) {
      run.stopped = true;
      break;
    }
    const bool late = simulation.steps() >= late_from;
    const engine::Invariants now = invariants(simulation);
    if (!w.energy_vs_reference) {
      energy_extremes(ch).keep((now.energy - w.start.energy) / w.energy_scale, late);
    }
    if (!w.momentum_vs_reference) {
      momentum_extremes(ch).keep((now.momentum - w.start.momentum) / w.momentum_scale, late);
    }
    if (const auto j = shared_sample(reference, simulation.time(), c.duration)) {
      compare_with_reference(simulation, reference, *j, w, late, run);
    }
  }
  run.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  run.steps = simulation.steps();
  clear_inapplicable(ch);
}

/// The blow-up, which voids the errors measured before it.
void record_blow_up(const engine::Simulation& simulation, StabilityRun& run) {
  if (const auto& blow_up = simulation.blow_up()) {
    run.blowup_time = blow_up->time;
    run.blowup_reason = "step " + std::to_string(blow_up->step) + ": " + blow_up->reason;
    run.orientation_error.reset();
    run.position_error.reset();
    run.momentum_error.reset();
  }
}

/// The interval of the reference's samples (see stability_reference).
double reference_interval(const StabilityCase& c) {
  const double base = c.duration / 100.0;
  if (c.dts.empty()) return base;
  const double largest = *std::max_element(c.dts.begin(), c.dts.end());
  if (largest >= c.duration) return base;
  for (const double dt : c.dts) {
    const double ratio = largest / dt;
    if (std::abs(ratio - std::round(ratio)) > 1e-9 * ratio) return base;
  }
  return largest * std::max(1.0, std::ceil(base / largest - 1e-9));
}

}  // namespace

StabilityReference stability_reference(const StabilityCase& c) {
  const engine::ReferenceMotion motion(c.bodies, c.initial);
  StabilityReference reference;
  try {
    reference.interval = reference_interval(c);
    reference.samples = motion.sample(reference.interval, c.duration);
  } catch (const tumble::InputError&) {
    return {};
  }
  reference.kind = motion.label();
  for (const std::vector<engine::BodyState>& states : reference.samples) {
    reference.invariants.push_back(
        engine::total_invariants(c.bodies, states, engine::InvariantSum::kAll));
    for (std::size_t i = 0; i < c.bodies.size(); ++i) {
      if (c.bodies[i].pivoted) continue;
      reference.motion_range =
          std::max(reference.motion_range, (states[i].position - c.initial[i].position).norm());
    }
  }
  return reference;
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
  } catch (const tumble::InputError& error) {  // the exact solution on a forced case
    run.note = error.what();
    return run;
  }
  engine::Simulation& simulation = *built;
  run.total_steps = simulation.total_steps();
  step_watching_invariants(c, simulation, reference, run, stop);
  if (run.stopped) return run;
  record_blow_up(simulation, run);
  run.motion_range = reference.motion_range;
  ReferenceErrors errors{run.orientation_error, run.momentum_error, std::nullopt};
  if (run.position_error && reference.motion_range > 0.0) {
    errors.position = *run.position_error / reference.motion_range;
  }
  run.outcome =
      classify(simulation.blow_up().has_value(), run.changes, kStabilityDriftThreshold, errors);
  return run;
}

}  // namespace tumble::app
