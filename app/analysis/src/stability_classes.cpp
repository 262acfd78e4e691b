#include "app/analysis/stability_classes.hpp"

#include <algorithm>
#include <cmath>

namespace tumble::app {

const char* outcome_name(StabilityOutcome outcome) {
  switch (outcome) {
    case StabilityOutcome::kStable:
      return "stable";
    case StabilityOutcome::kDrifting:
      return "drifting";
    case StabilityOutcome::kDamped:
      return "damped";
    case StabilityOutcome::kWrong:
      return "wrong";
    case StabilityOutcome::kBlewUp:
      return "blew up";
    case StabilityOutcome::kUnchecked:
      return "unchecked";
    case StabilityOutcome::kSkipped:
      return "skipped";
  }
  return "?";
}

StabilityOutcome classify(bool blew_up, const InvariantChanges& changes, double threshold,
                          const ReferenceErrors& errors) {
  if (blew_up) return StabilityOutcome::kBlewUp;
  // Bounded but wrong: the state is far from the reference's, or the energy is.
  const bool energy_wrong =
      changes.energy_applies &&
      std::max(changes.energy_max_gain, changes.energy_max_loss) > kWrongEnergyChange;
  const auto beyond = [](const std::optional<double>& error, double limit) {
    return error && *error > limit;
  };
  if (beyond(errors.orientation, kWrongOrientationError) ||
      beyond(errors.momentum, kWrongMomentumError) ||
      beyond(errors.position, kWrongPositionError) || energy_wrong) {
    return StabilityOutcome::kWrong;
  }
  if (!changes.energy_applies && !changes.momentum_applies) return StabilityOutcome::kUnchecked;
  const double gain = std::max(changes.energy_applies ? changes.energy_max_gain : 0.0,
                               changes.momentum_applies ? changes.momentum_max_gain : 0.0);
  const double loss = std::max(changes.energy_applies ? changes.energy_max_loss : 0.0,
                               changes.momentum_applies ? changes.momentum_max_loss : 0.0);
  if (gain <= threshold && loss <= threshold) return StabilityOutcome::kStable;
  const auto persistent_loss = [&](bool applies, double late_min, double late_max) {
    return applies && late_max < -threshold && late_max - late_min < 0.5 * -late_max;
  };
  const bool ends_lower =
      persistent_loss(changes.energy_applies, changes.energy_late_min, changes.energy_late_max) ||
      persistent_loss(changes.momentum_applies, changes.momentum_late_min,
                      changes.momentum_late_max);
  if (ends_lower && gain <= threshold) return StabilityOutcome::kDamped;
  return StabilityOutcome::kDrifting;
}

}  // namespace tumble::app
