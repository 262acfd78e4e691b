#pragma once
// Private to the engine: the stepper factories behind make_stepper, and what they share.

#include <memory>

#include "engine/body/rigid_body.hpp"
#include "engine/dynamics/integrators.hpp"

namespace tumble::engine::steppers {

/// Everything an integrator needs from the right-hand side at one state.
struct Rates {
  Eigen::Vector3d velocity;      ///< dx/dt
  Eigen::Vector3d acceleration;  ///< dv/dt (zero for pivoted bodies: the pivot holds them)
  Eigen::Vector3d omega;         ///< world angular velocity
  Eigen::Vector3d torque;        ///< dL/dt, world
};

/// The right-hand side at `state`; no force code runs for a body without force terms.
/// `inverse_moments` (1 / moments, kept by steppers that evaluate this often) saves the
/// divisions of angular_velocity().
inline Rates rates(const BodyModel& body, const BodyState& state,
                   const Eigen::Vector3d& inverse_moments) {
  const Eigen::Vector3d momentum_body = state.orientation.conjugate() * state.angular_momentum;
  Rates out{state.velocity, Eigen::Vector3d::Zero(),
            state.orientation * inverse_moments.cwiseProduct(momentum_body),
            Eigen::Vector3d::Zero()};
  if (!body.forces.empty()) {
    const Wrench w = wrench(body, state, out.omega);
    if (!body.pivoted) out.acceleration = w.force / body.mass;
    out.torque = w.torque;
  }
  return out;
}

inline Rates rates(const BodyModel& body, const BodyState& state) {
  return rates(body, state, body.moments.cwiseInverse());
}

/// The matrix of v x: cross_matrix(v) w = v x w.
inline Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

std::unique_ptr<BodyStepper> make_explicit_euler(const BodyModel& body);
std::unique_ptr<BodyStepper> make_semi_implicit_euler(const BodyModel& body);
std::unique_ptr<BodyStepper> make_lie_euler(const BodyModel& body);
std::unique_ptr<BodyStepper> make_seed_semi_implicit(const BodyModel& body);
std::unique_ptr<BodyStepper> make_implicit_euler(const BodyModel& body);
std::unique_ptr<BodyStepper> make_rk4(const BodyModel& body);
std::unique_ptr<BodyStepper> make_midpoint(const BodyModel& body);
std::unique_ptr<BodyStepper> make_dopri(const BodyModel& body, const StepSettings& settings);
std::unique_ptr<BodyStepper> make_splitting(const BodyModel& body, int order);
std::unique_ptr<BodyStepper> make_free_rotor(const BodyModel& body);
std::unique_ptr<BodyStepper> make_moser_veselov(const BodyModel& body);
std::unique_ptr<BodyStepper> make_exact(const BodyModel& body, const BodyState& initial);

}  // namespace tumble::engine::steppers
