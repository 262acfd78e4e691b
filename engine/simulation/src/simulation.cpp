// A run of independent bodies: fixed output steps, blow-up detection after each.
#include "engine/simulation/simulation.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace tumble::engine {
namespace {

std::string times(double ratio) {
  std::ostringstream out;
  out.precision(3);
  out << ratio << "x";
  return out.str();
}

}  // namespace

Simulation::Simulation(std::vector<BodyModel> bodies, std::vector<BodyState> initial,
                       const SimulationSettings& settings)
    : bodies_(std::move(bodies)), initial_(std::move(initial)), settings_(settings) {
  if (bodies_.size() != initial_.size()) {
    throw std::invalid_argument("Simulation: one initial state per body");
  }
  states_ = initial_;
  StepSettings step_settings;
  step_settings.tolerance = settings_.tolerance;
  step_settings.absolute_tolerance = settings_.absolute_tolerance;
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    update_pivot_kinematics(bodies_[i], states_[i]);
    // The steppers keep a reference to their body: bodies_ never reallocates after this.
    steppers_.push_back(make_stepper(settings_.integrator, bodies_[i], states_[i], step_settings));
    initial_energy_.push_back(energy(bodies_[i], states_[i]));
    // Fixed from the initial state and free of the origin and of the potentials' zero (§6): a
    // running scale would grow with a blowing-up run's own kinetic energy and hide it.
    initial_energy_scale_.push_back(energy_scale(bodies_[i], states_[i], settings_.duration));
    initial_momentum_.push_back(states_[i].angular_momentum.norm());
  }
  initial_ = states_;
}

StepCounts Simulation::step_counts() const {
  const int per_step = integrator_info(settings_.integrator).evaluations_per_step;
  StepCounts sum;
  for (std::size_t i = 0; i < steppers_.size(); ++i) {
    if (const std::optional<StepCounts> own = steppers_[i]->counts()) {
      sum.accepted += own->accepted;
      sum.rejected += own->rejected;
      sum.evaluations += own->evaluations;
      continue;
    }
    // The bodies up to the one that blew up stepped once more than the steps committed.
    const std::size_t calls = steps_ + (blow_up_ && i <= blow_up_->body ? 1 : 0);
    sum.accepted += calls;
    sum.evaluations += calls * static_cast<std::size_t>(per_step);
  }
  return sum;
}

std::size_t Simulation::total_steps() const {
  // The last step may be shorter; a duration within rounding of a whole number of steps
  // takes exactly that number.
  return static_cast<std::size_t>(std::ceil(settings_.duration / settings_.dt - 1e-9));
}

bool Simulation::step() {
  if (finished()) return false;
  // Times are whole multiples of dt (no accumulated rounding); the last step ends exactly at
  // the duration.
  const double next_time = steps_ + 1 == total_steps()
                               ? settings_.duration
                               : static_cast<double>(steps_ + 1) * settings_.dt;
  const double h = next_time - time_;
  next_ = states_;
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    const BodyModel& body = bodies_[i];
    BodyState& next = next_[i];
    steppers_[i]->step(next, time_, h);
    update_pivot_kinematics(body, next);

    // Blow-up: non-finite numbers, or an invariant grown past the limit.
    std::string reason;
    if (!next.finite()) {
      reason = "the state became non-finite";
    } else if (body.conservative() && initial_energy_scale_[i] > 0.0) {
      const double drift = std::abs(energy(body, next) - initial_energy_[i]);
      if (drift > (settings_.blowup_factor - 1.0) * initial_energy_scale_[i]) {
        reason = "energy drifted by " + times(drift / initial_energy_scale_[i]) +
                 " its scale (kinetic energy plus potential swings)";
      }
    }
    if (reason.empty() && body.torque_free() && initial_momentum_[i] > 0.0) {
      const double growth = next.angular_momentum.norm() / initial_momentum_[i];
      if (growth > settings_.blowup_factor) reason = "|L| grew " + times(growth);
    }
    if (!reason.empty()) {
      blow_up_ = BlowUp{i, steps_ + 1, next_time, reason};
      return false;
    }
  }
  states_.swap(next_);
  ++steps_;
  time_ = next_time;
  return true;
}

}  // namespace tumble::engine
