// The one reference motion: exact when every body is torque-free or a Lagrange top, otherwise
// dopri at kReferenceTolerance.
#include "engine/simulation/reference_motion.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>
#include <variant>

#include "base/errors.hpp"
#include "engine/simulation/simulation.hpp"

namespace tumble::engine {
namespace {

std::string short_number(double tolerance) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", tolerance);
  return buffer;
}

/// The uniform acceleration acting on a body (zero without gravity).
Eigen::Vector3d gravity_of(const BodyModel& body) {
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  for (const ForceTerm& term : body.forces) {
    if (const auto* gravity = std::get_if<Gravity>(&term)) g += gravity->acceleration;
  }
  return g;
}

}  // namespace

ReferenceMotion::ReferenceMotion(std::vector<BodyModel> bodies, std::vector<BodyState> initial,
                                 double tolerance)
    : bodies_(std::move(bodies)), initial_(std::move(initial)), tolerance_(tolerance) {
  const auto has = [&](auto predicate) {
    return std::all_of(bodies_.begin(), bodies_.end(), predicate);
  };
  if (has([](const BodyModel& body) { return body.torque_free(); })) {
    kind_ = Kind::kExact;
  } else if (has([](const BodyModel& body) {
               return body.torque_free() || is_lagrange_top(body);
             })) {
    kind_ = Kind::kExactWithTops;
  } else {
    kind_ = Kind::kDopri;
  }
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    update_pivot_kinematics(bodies_[i], initial_[i]);
    if (kind_ == Kind::kDopri) continue;
    const BodyState& start = initial_[i];
    if (!bodies_[i].torque_free()) {
      slot_.push_back(tops_.size());
      tops_.emplace_back(bodies_[i], start);
      continue;
    }
    // Initial angular velocity in principal axes: J^-1 R^T L.
    const Eigen::Vector3d omega_body =
        (start.orientation.conjugate() * start.angular_momentum).cwiseQuotient(bodies_[i].moments);
    slot_.push_back(free_.size());
    free_.emplace_back(bodies_[i].moments, start.orientation, omega_body);
  }
}

IntegratorKind ReferenceMotion::integrator() const {
  return kind_ == Kind::kDopri ? IntegratorKind::kDopri : IntegratorKind::kExact;
}

std::string ReferenceMotion::description() const {
  switch (kind_) {
    case Kind::kExact:
      return "exact torque-free solution (Jacobi elliptic functions)";
    case Kind::kExactWithTops:
      return "exact solution: torque-free bodies and heavy symmetric tops (elliptic functions "
             "and integrals)";
    case Kind::kDopri:
      break;
  }
  return "dopri at tolerance " + short_number(tolerance_);
}

std::string ReferenceMotion::label() const {
  switch (kind_) {
    case Kind::kExact:
      return "exact";
    case Kind::kExactWithTops:
      return "exact top";
    case Kind::kDopri:
      break;
  }
  return "dopri " + short_number(tolerance_);
}

BodyState ReferenceMotion::exact_state(std::size_t body, double t) const {
  // Orientation in closed form, L constant, the centre of mass on its parabola (gravity acts
  // at the centre of mass, so it leaves the rotation free) or carried by the pivot.
  if (!bodies_[body].torque_free()) return tops_[slot_[body]].at(t);  // a Lagrange top
  const BodyState& start = initial_[body];
  const Eigen::Vector3d g = gravity_of(bodies_[body]);
  BodyState state = start;
  state.orientation = free_[slot_[body]].at(t).orientation;
  state.position = start.position + start.velocity * t + 0.5 * t * t * g;
  state.velocity = start.velocity + t * g;
  update_pivot_kinematics(bodies_[body], state);
  return state;
}

std::vector<std::vector<BodyState>> ReferenceMotion::dopri_run(double interval,
                                                               double duration) const {
  SimulationSettings settings;
  settings.integrator = IntegratorKind::kDopri;
  settings.dt = interval;
  settings.duration = duration;
  settings.tolerance = tolerance_;
  settings.blowup_factor = std::numeric_limits<double>::infinity();  // stop on NaN/inf only
  Simulation simulation(bodies_, initial_, settings);
  std::vector<std::vector<BodyState>> samples;
  samples.reserve(simulation.total_steps());
  while (simulation.step()) samples.push_back(simulation.states());
  if (const auto& blow_up = simulation.blow_up()) {
    throw InputError("the reference (" + description() +
                     ") blew up at t = " + short_number(blow_up->time) + " s: " + blow_up->reason);
  }
  return samples;
}

std::vector<BodyState> ReferenceMotion::at(double t) const {
  if (kind_ == Kind::kDopri) return t > 0.0 ? dopri_run(t, t).back() : initial_;
  std::vector<BodyState> states;
  for (std::size_t i = 0; i < bodies_.size(); ++i) states.push_back(exact_state(i, t));
  return states;
}

std::vector<std::vector<BodyState>> ReferenceMotion::sample(double interval,
                                                            double duration) const {
  if (kind_ == Kind::kDopri) return dopri_run(interval, duration);
  // The instants of Simulation::step: whole multiples of the interval, the last the duration.
  const auto count = static_cast<std::size_t>(std::ceil(duration / interval - 1e-9));
  std::vector<std::vector<BodyState>> samples;
  samples.reserve(count);
  for (std::size_t k = 1; k <= count; ++k) {
    samples.push_back(at(k == count ? duration : static_cast<double>(k) * interval));
  }
  return samples;
}

std::optional<ReferenceMotion> ReferenceMotion::check_run() const {
  if (kind_ != Kind::kDopri) return std::nullopt;
  return ReferenceMotion(bodies_, initial_, kReferenceCheckTolerance);
}

}  // namespace tumble::engine
