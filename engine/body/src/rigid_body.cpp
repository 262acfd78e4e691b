// Kinematics, forces and energy of one body.
#include "engine/body/rigid_body.hpp"

#include <cmath>

namespace tumble::engine {
namespace {

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
// Spelled out for clang before 17, which does not deduce aggregate templates (P1816).
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

}  // namespace

bool BodyModel::torque_free() const {
  for (const ForceTerm& term : forces) {
    if (std::holds_alternative<Gravity>(term) && !pivoted) continue;  // acts at the centre of mass
    return false;
  }
  return true;
}

bool BodyModel::conservative() const {
  for (const ForceTerm& term : forces) {
    if (std::holds_alternative<ConstantTorque>(term)) return false;
    if (const auto* spring = std::get_if<Spring>(&term); spring && spring->damping != 0.0)
      return false;
  }
  return true;
}

bool BodyState::finite() const {
  return position.allFinite() && velocity.allFinite() && orientation.coeffs().allFinite() &&
         angular_momentum.allFinite();
}

Eigen::Vector3d angular_velocity(const BodyModel& body, const BodyState& state) {
  const Eigen::Vector3d local = state.orientation.conjugate() * state.angular_momentum;
  return state.orientation * local.cwiseQuotient(body.moments);
}

BodyState spinning_state(const BodyModel& body, const Eigen::Quaterniond& orientation,
                         const Eigen::Vector3d& omega_principal) {
  BodyState state;
  state.orientation = orientation.normalized();
  state.angular_momentum = state.orientation * body.moments.cwiseProduct(omega_principal);
  return state;
}

Wrench wrench(const BodyModel& body, const BodyState& state, const Eigen::Vector3d& omega) {
  Wrench out;
  for (const ForceTerm& term : body.forces) {
    std::visit(Overloaded{
                   [&](const Gravity& gravity) {
                     const Eigen::Vector3d weight = body.mass * gravity.acceleration;
                     out.force += weight;
                     if (body.pivoted) {
                       out.torque += (state.orientation * body.center_offset).cross(weight);
                     }
                   },
                   [&](const ConstantTorque& torque) {
                     out.torque += torque.body_frame
                                       ? Eigen::Vector3d(state.orientation * torque.torque)
                                       : torque.torque;
                   },
                   [&](const Spring& spring) {
                     const Eigen::Vector3d arm = state.orientation * spring.attach;
                     const Eigen::Vector3d point = rotation_centre(body, state) + arm;
                     Eigen::Vector3d point_velocity = omega.cross(arm);
                     if (!body.pivoted) point_velocity += state.velocity;
                     const Eigen::Vector3d force = -spring.stiffness * (point - spring.anchor) -
                                                   spring.damping * point_velocity;
                     out.force += force;
                     out.torque += arm.cross(force);
                   },
               },
               term);
  }
  return out;
}

double energy(const BodyModel& body, const BodyState& state) {
  // Rotational energy about the rotation centre; for a pivoted body it includes the motion of
  // the centre of mass, for a free body the translation adds m v^2 / 2.
  double total = 0.5 * angular_velocity(body, state).dot(state.angular_momentum);
  if (!body.pivoted) total += 0.5 * body.mass * state.velocity.squaredNorm();
  for (const ForceTerm& term : body.forces) {
    if (const auto* gravity = std::get_if<Gravity>(&term)) {
      total -= body.mass * gravity->acceleration.dot(state.position);
    } else if (const auto* spring = std::get_if<Spring>(&term)) {
      const Eigen::Vector3d point =
          rotation_centre(body, state) + state.orientation * spring->attach;
      total += 0.5 * spring->stiffness * (point - spring->anchor).squaredNorm();
    }
  }
  return total;
}

Invariants invariants(const BodyModel& body, const BodyState& state) {
  return {energy(body, state), state.angular_momentum.norm()};
}

Invariants total_invariants(const std::vector<BodyModel>& bodies,
                            const std::vector<BodyState>& states, InvariantSum which) {
  const bool all = which == InvariantSum::kAll;
  Invariants sum;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (all || bodies[i].conservative()) sum.energy += energy(bodies[i], states[i]);
    if (all || bodies[i].torque_free()) sum.momentum += states[i].angular_momentum.norm();
  }
  return sum;
}

Eigen::Vector3d rotation_centre(const BodyModel& body, const BodyState& state) {
  return body.pivoted ? body.pivot : state.position;
}

void update_pivot_kinematics(const BodyModel& body, BodyState& state) {
  if (!body.pivoted) return;
  const Eigen::Vector3d arm = state.orientation * body.center_offset;
  state.position = body.pivot + arm;
  state.velocity = angular_velocity(body, state).cross(arm);
}

Eigen::Quaterniond body_orientation(const BodyModel& body, const BodyState& state) {
  // principal -> world composed with body -> principal.
  return (state.orientation * body.principal_to_body.conjugate()).normalized();
}

double orientation_angle(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  const Eigen::Quaterniond d = a.conjugate() * b;
  return 2.0 * std::atan2(d.vec().norm(), std::abs(d.w()));
}

}  // namespace tumble::engine
