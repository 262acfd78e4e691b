#include "app/analysis/error_measures.hpp"

#include <algorithm>
#include <cmath>
#include <exception>

#include "engine/input_error.hpp"
#include "engine/integrators.hpp"
#include "engine/torque_free_exact.hpp"

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

/// Samples of an adaptive run at `tolerance` with output step grid.interval.
std::vector<std::vector<ReferenceState>> dopri_samples(
    const std::vector<engine::BodyModel>& bodies, const std::vector<engine::BodyState>& initial,
    engine::SimulationSettings settings, const SampleGrid& grid, double tolerance) {
  settings.integrator = engine::IntegratorKind::kDopri;
  settings.dt = grid.interval;
  settings.duration = grid.duration;
  settings.tolerance = tolerance;
  engine::Simulation simulation(bodies, initial, settings);
  std::vector<std::vector<ReferenceState>> samples;
  samples.reserve(grid.count());
  while (simulation.step()) {
    std::vector<ReferenceState> row;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      row.push_back(reference_state(bodies[i], simulation.states()[i]));
    }
    samples.push_back(std::move(row));
  }
  if (const auto& blow_up = simulation.blow_up()) {
    throw engine::InputError("the reference (dopri at tolerance " + std::to_string(tolerance) +
                             ") blew up at t = " + std::to_string(blow_up->time) + " s: " +
                             blow_up->reason);
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
                         const std::vector<engine::BodyState>& initial,
                         const engine::SimulationSettings& settings, const SampleGrid& grid) {
  Reference reference;
  const bool torque_free = std::all_of(bodies.begin(), bodies.end(),
                                       [](const engine::BodyModel& b) { return b.torque_free(); });
  if (torque_free) {
    // Closed form at every sample; omega_body = J^-1 R^T L at t = 0.
    reference.description = "exact torque-free solution (Jacobi elliptic functions)";
    std::vector<engine::TorqueFreeMotion> motions;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      const Eigen::Vector3d omega_body =
          (initial[i].orientation.conjugate() * initial[i].angular_momentum)
              .cwiseQuotient(bodies[i].moments);
      motions.emplace_back(bodies[i].moments, initial[i].orientation, omega_body);
    }
    for (std::size_t k = 1; k <= grid.count(); ++k) {
      std::vector<ReferenceState> row;
      for (std::size_t i = 0; i < bodies.size(); ++i) {
        const auto exact = motions[i].at(grid.time(k));
        row.push_back({exact.orientation, exact.orientation * exact.omega_body,
                       motions[i].angular_momentum_world()});
      }
      reference.samples.push_back(std::move(row));
    }
    return reference;
  }

  // Forced: dopri at 1e-13, checked against 1e-12.
  reference.description = "dopri at tolerance 1e-13";
  reference.samples = dopri_samples(bodies, initial, settings, grid, kReferenceTolerance);
  const auto check = dopri_samples(bodies, initial, settings, grid, kCheckTolerance);
  ReferenceCheck figures;
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
    energy0_.push_back(engine::energy(bodies[i], initial[i]));
    momentum0_.push_back(initial[i].angular_momentum.norm());
  }
}

void ErrorMeter::observe(std::size_t k, const std::vector<engine::BodyState>& states) {
  const auto& row = reference_.samples.at(k - 1);
  ErrorFigures& f = figures_;
  f.orientation_final = f.omega_final = f.momentum_final = 0.0;
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    const engine::BodyState& state = states[i];
    const ReferenceState& ref = row[i];
    f.orientation_final =
        std::max(f.orientation_final, engine::orientation_angle(ref.orientation, state.orientation));
    f.omega_final = std::max(
        f.omega_final, relative_difference(engine::angular_velocity(bodies_[i], state), ref.omega));
    f.momentum_final =
        std::max(f.momentum_final, relative_difference(state.angular_momentum, ref.momentum));
    f.energy_drift_max =
        std::max(f.energy_drift_max, drift(engine::energy(bodies_[i], state), energy0_[i]));
    f.momentum_norm_drift_max =
        std::max(f.momentum_norm_drift_max, drift(state.angular_momentum.norm(), momentum0_[i]));
  }
  f.orientation_max = std::max(f.orientation_max, f.orientation_final);
  f.omega_max = std::max(f.omega_max, f.omega_final);
  f.momentum_max = std::max(f.momentum_max, f.momentum_final);
  ++f.samples;
}

}  // namespace tumble::app
