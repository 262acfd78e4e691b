#pragma once
/// @file The reference every integrator is measured against, chosen one way everywhere: the
/// exact solution when every body has one (torque-free bodies, engine/PHYSICS.md §4, and heavy
/// symmetric tops, §4b), otherwise dopri at kReferenceTolerance.
///
/// `tumble bench`, `compare` (the grey ghost of the overlay), `stability` and `simulate` all
/// take their reference from here, so they agree on what "the reference" is and say so with
/// the same words.

#include <optional>
#include <string>
#include <vector>

#include "engine/body/rigid_body.hpp"
#include "engine/dynamics/integrators.hpp"
#include "engine/exact/lagrange_top.hpp"
#include "engine/exact/torque_free_exact.hpp"

namespace tumble::engine {

/// Local error tolerance of the dopri reference of forced problems. A decade below the
/// tightest tolerance `tumble bench` sweeps by default (1e-12), so the reference stays ahead
/// of every run it judges.
inline constexpr double kReferenceTolerance = 1e-13;

/// Tolerance of the check run of a dopri reference: a decade looser, so the difference of the
/// two is about the check run's own error, an upper bound on the reference's.
inline constexpr double kReferenceCheckTolerance = 1e-12;

/// The reference motion of a set of independent bodies from their initial states.
class ReferenceMotion {
 public:
  enum class Kind {
    kExact,          ///< every body is torque-free: TorqueFreeMotion, position in closed form
    kExactWithTops,  ///< every body torque-free or a Lagrange top (some one): LagrangeTop too
    kDopri,          ///< some other body has torques: adaptive Dormand-Prince at tolerance()
  };

  /// `tolerance` is dopri's (unused when the exact solution applies). Throws
  /// std::invalid_argument for moments the exact solution refuses (see TorqueFreeMotion).
  ReferenceMotion(std::vector<BodyModel> bodies, std::vector<BodyState> initial,
                  double tolerance = kReferenceTolerance);

  Kind kind() const { return kind_; }
  /// The integrator that reproduces the reference in a Simulation: kExact (for both exact
  /// kinds) or kDopri.
  IntegratorKind integrator() const;
  /// dopri's local error tolerance (meaningful for kDopri only).
  double tolerance() const { return tolerance_; }
  /// "exact torque-free solution (Jacobi elliptic functions)", "exact solution: torque-free
  /// bodies and heavy symmetric tops (elliptic functions and integrals)" or "dopri at
  /// tolerance 1e-13".
  std::string description() const;
  /// Short form for tables: "exact", "exact top" or "dopri 1e-13".
  std::string label() const;

  /// Every body's state at time t >= 0 (dopri: one run with a single output step to t).
  std::vector<BodyState> at(double t) const;

  /// Every body's state after each step of a run with output step `interval` to `duration`,
  /// at the instants engine::Simulation reports: k * interval, the last exactly at `duration`.
  /// [step - 1][body]. Throws InputError when the dopri run produces a non-finite state.
  std::vector<std::vector<BodyState>> sample(double interval, double duration) const;

  /// For a dopri reference, the same reference at kReferenceCheckTolerance (how far to trust
  /// it); nothing for the exact solutions.
  std::optional<ReferenceMotion> check_run() const;

 private:
  BodyState exact_state(std::size_t body, double t) const;
  std::vector<std::vector<BodyState>> dopri_run(double interval, double duration) const;

  std::vector<BodyModel> bodies_;
  std::vector<BodyState> initial_;  ///< pivot kinematics applied
  double tolerance_;
  Kind kind_;
  std::vector<TorqueFreeMotion> free_;  ///< per torque-free body, exact kinds only
  std::vector<LagrangeTop> tops_;       ///< per Lagrange top, kExactWithTops only
  std::vector<std::size_t> slot_;       ///< body -> index in free_ or tops_
};

}  // namespace tumble::engine
