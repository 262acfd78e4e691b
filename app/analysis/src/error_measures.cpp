#include "app/analysis/error_measures.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <sstream>

#include "engine/simulation/reference_motion.hpp"

namespace tumble::app {
namespace {

/// |value - initial| / |initial|, or absolute when the initial value is zero.
double drift(double value, double initial) {
  const double change = std::abs(value - initial);
  return initial != 0.0 ? change / std::abs(initial) : change;
}

ReferenceState reference_state(const engine::BodyModel& body, const engine::BodyState& state) {
  return {state.orientation, engine::angular_velocity(body, state), state.angular_momentum};
}

/// A reference's samples on the grid.
std::vector<std::vector<ReferenceState>> grid_samples(const engine::ReferenceMotion& motion,
                                                      const std::vector<engine::BodyModel>& bodies,
                                                      const SampleGrid& grid) {
  std::vector<std::vector<ReferenceState>> samples;
  for (const std::vector<engine::BodyState>& states : motion.sample(grid.interval, grid.duration)) {
    std::vector<ReferenceState> row;
    for (std::size_t i = 0; i < bodies.size(); ++i)
      row.push_back(reference_state(bodies[i], states[i]));
    samples.push_back(std::move(row));
  }
  return samples;
}

}  // namespace

std::size_t SampleGrid::count() const {
  return static_cast<std::size_t>(std::ceil(duration / interval - 1e-9));
}

double SampleGrid::time(std::size_t k) const {
  return k >= count() ? duration : static_cast<double>(k) * interval;
}

double relative_difference(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const double scale = b.norm();
  const double difference = (a - b).norm();
  return scale > 0.0 ? difference / scale : difference;
}

Reference make_reference(const std::vector<engine::BodyModel>& bodies,
                         const std::vector<engine::BodyState>& initial, const SampleGrid& grid) {
  const engine::ReferenceMotion motion(bodies, initial);
  Reference reference;
  reference.description = motion.description();
  reference.samples = grid_samples(motion, bodies, grid);
  const std::optional<engine::ReferenceMotion> check_run = motion.check_run();
  if (!check_run) return reference;

  // Forced: how far the reference is from its check run.
  const auto check = grid_samples(*check_run, bodies, grid);
  ReferenceCheck figures;
  std::ostringstream runs;  // "dopri 1e-13 against 1e-12"
  runs << motion.label() << " against " << check_run->tolerance();
  figures.runs = runs.str();
  for (std::size_t k = 0; k < check.size() && k < reference.samples.size(); ++k) {
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      const ReferenceState& a = check[k][i];
      const ReferenceState& b = reference.samples[k][i];
      figures.orientation =
          std::max(figures.orientation, engine::orientation_angle(b.orientation, a.orientation));
      figures.omega = std::max(figures.omega, relative_difference(a.omega, b.omega));
      figures.momentum = std::max(figures.momentum, relative_difference(a.momentum, b.momentum));
    }
  }
  reference.check = figures;
  return reference;
}

ErrorMeter::ErrorMeter(const std::vector<engine::BodyModel>& bodies,
                       const std::vector<engine::BodyState>& initial, const Reference& reference)
    : bodies_(bodies), reference_(reference) {
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const engine::Invariants start = engine::invariants(bodies[i], initial[i]);
    energy0_.push_back(start.energy);
    momentum0_.push_back(start.momentum);
  }
}

void ErrorMeter::observe(std::size_t k, const std::vector<engine::BodyState>& states) {
  const auto& row = reference_.samples.at(k - 1);
  ErrorFigures& f = figures_;
  f.orientation_final = f.omega_final = f.momentum_final = 0.0;
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    const engine::BodyState& state = states[i];
    const ReferenceState& ref = row[i];
    f.orientation_final = std::max(f.orientation_final,
                                   engine::orientation_angle(ref.orientation, state.orientation));
    f.omega_final = std::max(
        f.omega_final, relative_difference(engine::angular_velocity(bodies_[i], state), ref.omega));
    f.momentum_final =
        std::max(f.momentum_final, relative_difference(state.angular_momentum, ref.momentum));
    const engine::Invariants now = engine::invariants(bodies_[i], state);
    f.energy_drift_max = std::max(f.energy_drift_max, drift(now.energy, energy0_[i]));
    f.momentum_norm_drift_max =
        std::max(f.momentum_norm_drift_max, drift(now.momentum, momentum0_[i]));
  }
  f.orientation_max = std::max(f.orientation_max, f.orientation_final);
  f.omega_max = std::max(f.omega_max, f.omega_final);
  f.momentum_max = std::max(f.momentum_max, f.momentum_final);
  ++f.samples;
}

}  // namespace tumble::app
