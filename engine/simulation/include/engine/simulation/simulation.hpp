#pragma once
/// @file Runs bodies forward with one integrator, watching for blow-ups.

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/body/rigid_body.hpp"
#include "engine/dynamics/integrators.hpp"

namespace tumble::engine {

struct SimulationSettings {
  IntegratorKind integrator = IntegratorKind::kRk4;
  double dt = 1e-3;                 ///< s
  double duration = 1.0;            ///< s
  double tolerance = 1e-10;         ///< adaptive integrators: relative tolerance (StepSettings)
  double absolute_tolerance = 0.0;  ///< adaptive integrators: absolute tolerance (StepSettings)
  double blowup_factor = 10.0;      ///< energy or |L| growth that counts as a blow-up
};

/// Where and why a run blew up.
struct BlowUp {
  std::size_t body = 0;
  std::size_t step = 0;  ///< the step that produced the bad state (1-based)
  double time = 0.0;     ///< simulation time after that step
  std::string reason;    ///< e.g. "non-finite state", "energy grew 12.5x"
};

/// A run of several independent bodies with one integrator and a fixed output step dt.
class Simulation {
 public:
  /// Throws InputError when the integrator cannot handle a body (see make_stepper).
  Simulation(std::vector<BodyModel> bodies, std::vector<BodyState> initial,
             const SimulationSettings& settings);

  /// Number of dt steps to cover the duration (the last step may be shorter).
  std::size_t total_steps() const;
  bool finished() const { return steps_ >= total_steps() || blow_up_.has_value(); }

  /// Advances every body by one step. Returns false (and records the blow-up, leaving the
  /// states at their last good values) when a body's state goes bad.
  bool step();

  double time() const { return time_; }
  std::size_t steps() const { return steps_; }
  const std::vector<BodyModel>& bodies() const { return bodies_; }
  const std::vector<BodyState>& states() const { return states_; }
  const std::vector<BodyState>& initial_states() const { return initial_; }
  const std::optional<BlowUp>& blow_up() const { return blow_up_; }
  const SimulationSettings& settings() const { return settings_; }

  /// The steppers' counts summed over the bodies (engine/PHYSICS.md §5): a stepper's own
  /// (dopri), else one accepted step per call with the catalog's evaluations_per_step each.
  StepCounts step_counts() const;

 private:
  std::vector<BodyModel> bodies_;
  std::vector<BodyState> initial_;
  std::vector<BodyState> states_;
  std::vector<std::unique_ptr<BodyStepper>> steppers_;
  std::vector<BodyState> next_;  ///< scratch: all bodies step before any is committed
  std::vector<double> initial_energy_;
  std::vector<double> initial_energy_scale_;
  std::vector<double> initial_momentum_;
  SimulationSettings settings_;
  double time_ = 0.0;
  std::size_t steps_ = 0;
  std::optional<BlowUp> blow_up_;
};

}  // namespace tumble::engine
