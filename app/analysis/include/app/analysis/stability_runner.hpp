#pragma once
/// @file One run of `tumble stability`: a case under one integrator at one dt, stepped through
/// engine::Simulation (which detects blow-ups) while the signed changes of the invariants that
/// apply are kept (energy of conservative bodies, |L| of torque-free ones, summed over bodies),
/// then classified and measured at the end against the case's reference.

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "app/analysis/stability_classes.hpp"
#include "app/analysis/stability_suite.hpp"
#include "engine/body/rigid_body.hpp"
#include "engine/dynamics/integrators.hpp"

namespace tumble::app {

/// The case's reference motion sampled through the run, and what it comes from ("none": no
/// samples).
struct StabilityReference {
  std::string kind = "none";
  double interval = 0.0;  ///< s between samples; the last sample is at the case's end
  std::vector<std::vector<engine::BodyState>>
      samples;                                 ///< [sample][body], at interval, 2 interval...
  std::vector<engine::Invariants> invariants;  ///< per sample, summed over every body
  /// The farthest any free body gets from its start over the samples, m (0: none moves).
  double motion_range = 0.0;
};

/// The case's engine::ReferenceMotion (the exact solution when every body is torque-free
/// or a heavy symmetric top, else dopri at engine::kReferenceTolerance) sampled every `interval`:
/// duration / 100, or for a case whose steps all divide the largest one, the smallest multiple of
/// that step not below duration / 100 (so that every run shares every sample). "none" when that run
/// fails.
StabilityReference stability_reference(const StabilityCase& c);

/// What one run of the sweep found.
struct StabilityRun {
  std::string case_name;
  std::string integrator;
  double dt = 0.0;
  double rate_dt = 0.0;  ///< the case's rate x dt, or dt when it has no rate
  double duration = 0.0;
  std::size_t steps = 0;
  std::size_t total_steps = 0;
  StabilityOutcome outcome = StabilityOutcome::kSkipped;
  InvariantChanges changes;  ///< all zero for the invariants that do not apply
  std::optional<double> blowup_time;
  std::string blowup_reason;
  /// The largest over the bodies and over the instants the run shares with the reference's
  /// samples (always the end); measured when the run did not blow up and there is a reference.
  std::optional<double> orientation_error;  ///< rad
  std::optional<double> position_error;     ///< m
  std::optional<double> momentum_error;     ///< |L - L_ref| / |L_ref| (world vector)
  double motion_range = 0.0;                ///< StabilityReference::motion_range, m
  std::size_t reference_instants = 0;       ///< how many instants were compared
  std::string reference;                    ///< StabilityReference::kind
  double wall_seconds = 0.0;                ///< the stepping loop
  std::string note;                         ///< why a skipped run was not made
  bool stopped = false;  ///< `stop` said so part-way: the run is incomplete, not to be reported
};

/// Runs case `c` under `info` at step `dt`. Skipped (with the reason in `note`) when the case
/// names other integrators or the simulation cannot be built (the exact solution on a forced
/// case); the errors are measured only when the run did not blow up and `reference` has
/// samples. `stop`, when given, is asked every kStopCheckSteps steps; when it says so the
/// run ends there with `stopped` set.
StabilityRun run_stability_case(const StabilityCase& c, const engine::IntegratorInfo& info,
                                double dt, const StabilityReference& reference,
                                const std::function<bool()>& stop = {});

/// Steps between two looks at `stop` in a stability run: often enough to stop within
/// milliseconds, rare enough to cost nothing beside the invariants computed every step.
inline constexpr std::size_t kStopCheckSteps = 1024;

}  // namespace tumble::app
