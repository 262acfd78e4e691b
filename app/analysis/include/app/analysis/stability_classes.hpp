#pragma once
/// @file The classes `tumble stability` sorts runs into, and the rules that sort them
/// (engine/PHYSICS.md §7).

#include <optional>

namespace tumble::app {

/// The relative drift above which a run is no longer `stable` (energy and |L|, over the run).
inline constexpr double kStabilityDriftThreshold = 1e-3;
/// The energy error, relative to the origin-free energy scale, above which a bounded run is
/// `wrong`.
inline constexpr double kWrongEnergyChange = 1e-2;
/// The orientation error against the reference (rad) above which a bounded run is `wrong`.
inline constexpr double kWrongOrientationError = 0.1;
/// The world angular momentum error against the reference, relative to |L_ref|, above which a
/// bounded run is `wrong` (the vector: a run may keep |L| and turn L, engine/PHYSICS.md §2).
inline constexpr double kWrongMomentumError = 1e-2;
/// The position error against the reference, relative to the reference's range of motion (the
/// farthest its free bodies get from their start), above which a bounded run is `wrong`.
inline constexpr double kWrongPositionError = 0.1;

/// A run's largest errors against the reference (over the bodies and the shared instants);
/// absent when not measured.
struct ReferenceErrors {
  std::optional<double> orientation;  ///< rad
  std::optional<double> momentum;     ///< |L - L_ref| / |L_ref|
  std::optional<double> position;     ///< |x - x_ref| / the reference's range of motion
};

/// The outcome of one run.
enum class StabilityOutcome { kStable, kDrifting, kDamped, kWrong, kBlewUp, kUnchecked, kSkipped };
/// The number of outcomes (for counting them).
inline constexpr int kStabilityOutcomeCount = 7;

/// The outcome as written in the outputs: "stable", "drifting", "damped", "wrong" (bounded but
/// wrong), "blew up", "unchecked" (nothing to check against), "skipped".
const char* outcome_name(StabilityOutcome outcome);

/// How the invariants changed over one run, relative to the origin-free energy scale of the case
/// (engine::energy_scale; |L0| for |L|; absolute when the scale is 0). Signed: positive is
/// growth, negative is loss. For a conservative (torque-free) case the energy (|L|) is compared
/// with its initial value after every step; otherwise, when the case has a reference, the
/// energy (|L|) of every body with the reference's at the instants the run shares with it.
struct InvariantChanges {
  bool energy_applies = false;
  bool momentum_applies = false;
  double energy_final = 0.0;     ///< (E_end - E_ref) / S
  double energy_max_gain = 0.0;  ///< max over the run of (E - E_ref) / S, >= 0
  double energy_max_loss = 0.0;  ///< max over the run of (E_ref - E) / S, >= 0
  double energy_late_min = 0.0;  ///< min of (E - E_ref) / S over the last quarter of the steps
  double energy_late_max = 0.0;  ///< max of (E - E_ref) / S over the last quarter of the steps
  double momentum_final = 0.0;
  double momentum_max_gain = 0.0;
  double momentum_max_loss = 0.0;
  double momentum_late_min = 0.0;
  double momentum_late_max = 0.0;
};

/// The classification rules (documented in the report), in this order:
///  1. `blew up` when the simulation reported a blow-up;
///  2. `wrong` when the run stayed bounded but is wrong: an error of `errors` beyond its limit
///     (kWrongOrientationError, kWrongMomentumError, kWrongPositionError), or the energy off
///     by more than kWrongEnergyChange (max gain or max loss, when the energy applies);
///  3. `unchecked` when neither energy nor |L| can be checked;
///  4. `stable` when every applicable invariant stayed within `threshold` over the whole run
///     (max gain and max loss both <= threshold);
///  5. `damped` when an invariant stays below its reference by more than `threshold` over the
///     whole last quarter of the run (late max < -threshold), swinging there by less than half
///     its loss (late max - late min < |late max| / 2: a wide bounded oscillation, as Verlet's
///     on a spring, is not damping), and no invariant ever gained more than `threshold`;
///  6. `drifting` otherwise (bounded, but a gain beyond `threshold`, or swings beyond it).
StabilityOutcome classify(bool blew_up, const InvariantChanges& changes, double threshold,
                          const ReferenceErrors& errors = {});

}  // namespace tumble::app
