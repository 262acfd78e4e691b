#pragma once
// Errors of a run against a reference, sampled on a grid common to every run of a scene (the
// measurement half of `tumble bench`).
//
// The grid: samples at k * interval for k = 1 .. K - 1 and the last one at the duration, where
// interval is the largest step of the sweep (every swept step divides it). A run with step dt
// samples after every (interval / dt)-th step and after its last step, so every run of a scene
// is compared at the same instants, and the reference is computed once.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "engine/body/rigid_body.hpp"
#include "engine/simulation/simulation.hpp"

namespace tumble::app {

/// The sampling instants of a scene's runs (t = 0 is not sampled: every error is zero there).
struct SampleGrid {
  double interval = 0.0;  ///< s
  double duration = 0.0;  ///< s
  /// Number of samples K (the same count as engine::Simulation::total_steps at `interval`).
  std::size_t count() const;
  /// Time of sample k (1-based): k * interval, the last exactly the duration.
  double time(std::size_t k) const;
};

/// What the reference says about one body at one sample.
struct ReferenceState {
  Eigen::Quaterniond orientation;  ///< principal frame to world
  Eigen::Vector3d omega;           ///< world angular velocity, rad/s
  Eigen::Vector3d momentum;        ///< world angular momentum about the rotation centre
};

/// How far the forced-problem reference (dopri at engine::kReferenceTolerance) is from its
/// check run (at engine::kReferenceCheckTolerance).
struct ReferenceCheck {
  std::string runs;          ///< "dopri 1e-13 against 1e-12"
  double orientation = 0.0;  ///< max geodesic angle over samples and bodies, rad
  double omega = 0.0;        ///< max relative difference of world omega
  double momentum = 0.0;     ///< max relative difference of world L
};

/// The reference trajectory of a scene on its grid.
struct Reference {
  std::string description;                           ///< e.g. "exact torque-free solution"
  std::vector<std::vector<ReferenceState>> samples;  ///< [k - 1][body]
  std::optional<ReferenceCheck> check;               ///< forced problems only
};

/// The scene's engine::ReferenceMotion on the grid, with its check run when it is dopri.
/// Throws tumble::InputError when the reference blows up.
Reference make_reference(const std::vector<engine::BodyModel>& bodies,
                         const std::vector<engine::BodyState>& initial, const SampleGrid& grid);

/// The figures of one run; each is the maximum over the scene's bodies.
struct ErrorFigures {
  double orientation_final = 0.0;  ///< geodesic angle at the last sample, rad
  double orientation_max = 0.0;    ///< rad
  double omega_final = 0.0;        ///< |w - w_ref| / |w_ref| (world)
  double omega_max = 0.0;
  double momentum_final = 0.0;  ///< |L - L_ref| / |L_ref| (world)
  double momentum_max = 0.0;
  double energy_drift_max = 0.0;         ///< max |E - E0| / |E0|
  double momentum_norm_drift_max = 0.0;  ///< max | |L| - |L0| | / |L0|
  std::size_t samples = 0;               ///< samples observed
};

/// Accumulates a run's errors sample by sample.
class ErrorMeter {
 public:
  ErrorMeter(const std::vector<engine::BodyModel>& bodies,
             const std::vector<engine::BodyState>& initial, const Reference& reference);

  /// Compares the run's `states` with the reference at sample k (1-based).
  void observe(std::size_t k, const std::vector<engine::BodyState>& states);

  const ErrorFigures& figures() const { return figures_; }

 private:
  const std::vector<engine::BodyModel>& bodies_;
  const Reference& reference_;
  std::vector<double> energy0_;
  std::vector<double> momentum0_;
  ErrorFigures figures_;
};

/// |a - b| / |b|, or |a - b| when b = 0.
double relative_difference(const Eigen::Vector3d& a, const Eigen::Vector3d& b);

}  // namespace tumble::app
