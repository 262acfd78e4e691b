#pragma once
/// @file The integrator family: names, properties, and one stepper per body.

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/body/rigid_body.hpp"

namespace tumble::engine {

enum class IntegratorKind {
  kExplicitEuler,
  kSemiImplicitEuler,
  kLieEuler,
  kSeedSemiImplicit,
  kImplicitEuler,
  kRk4,
  kMidpoint,
  kSplitting,
  kSplitting4,
  kFreeRotor,
  kMoserVeselov,
  kDopri,
  kExact,
};

/// What a user needs to pick an integrator.
struct IntegratorInfo {
  IntegratorKind kind;
  std::string name;        ///< as written in scenes and on the command line
  int order;               ///< global order in dt (0: does not converge; -1: exact)
  bool adaptive;           ///< takes --tolerance and sub-steps on its own
  bool needs_torque_free;  ///< refuses scenes with torques (the exact solution)
  std::string properties;  ///< one line: what it keeps and what it breaks
  /// Right-hand-side evaluations per step (one evaluation: the forces and the rotational rate
  /// at one state, whether or not the body has force terms; engine/PHYSICS.md §5); 0 for
  /// steppers that count their own (dopri).
  int evaluations_per_step = 0;
};

/// Every integrator, in the order --list-integrators shows them.
const std::vector<IntegratorInfo>& integrator_catalog();
const IntegratorInfo& integrator_info(IntegratorKind kind);
std::optional<IntegratorKind> integrator_from_name(std::string_view name);

/// Settings shared by every stepper. dopri's error norm (engine/PHYSICS.md §3): each local error
/// (the positions, the velocities and world L as 3-vectors, the orientation as a rotation
/// angle) against `absolute_tolerance + tolerance * |y|`, |y| the vector's length (1 for the
/// orientation, a unit quaternion); a step is kept when no error exceeds its scale.
struct StepSettings {
  double tolerance = 1e-10;         ///< dopri: relative tolerance rtol (positive, finite)
  double absolute_tolerance = 0.0;  ///< dopri: absolute tolerance atol, in each quantity's
                                    ///< SI unit (m, m/s, rad, kg m^2/s); >= 0, finite
};

/// What is wrong with `settings` for an adaptive integrator ("tolerance: expected ...",
/// naming the field), or nothing.
std::optional<std::string> step_settings_problem(const StepSettings& settings);

/// What a stepper has done so far: accepted and rejected steps and right-hand-side
/// evaluations (engine/PHYSICS.md §5).
struct StepCounts {
  std::size_t accepted = 0;
  std::size_t rejected = 0;
  std::size_t evaluations = 0;
};

/// Advances one body. Steppers may hold state (the adaptive step size, the exact solution's
/// constants), so a run creates one per body. step() never throws: a failure shows up as a
/// non-finite state, which the simulation detects.
class BodyStepper {
 public:
  virtual ~BodyStepper() = default;
  /// Advances `state` from time t to t + h.
  virtual void step(BodyState& state, double t, double h) = 0;
  /// The counts since construction, for steppers that keep their own (dopri: its sub-steps and
  /// rejections; an implicit method could count its solver's evaluations). nullopt: a fixed
  /// step, one accepted step per call with the catalog's evaluations_per_step each
  /// (Simulation::step_counts does that arithmetic).
  virtual std::optional<StepCounts> counts() const { return std::nullopt; }
};

/// A stepper of `kind` for `body` starting from `initial` at t = 0. Throws InputError when the
/// integrator cannot handle the body (the exact solution with torques).
std::unique_ptr<BodyStepper> make_stepper(IntegratorKind kind, const BodyModel& body,
                                          const BodyState& initial, const StepSettings& settings);

}  // namespace tumble::engine
