// Splitting integrators: rotation splitting, its 4th-order composition, free-rotor.
//
// (The exact integrator, a closed form rather than a step, is in exact_stepper.cpp.)
// All are "kick, drift, kick": a half kick of forces and torques (v += a h/2, L += tau h/2),
// a drift of the free motion, a half kick. They differ in the free rotation:
// - splitting: Dullweber, Leimkuhler and McLachlan, "Symplectic splitting methods for rigid
//   body molecular dynamics", J. Chem. Phys. 107 (1997): the kinetic energy
//   sum L_i^2 / (2 J_i) is split into its three terms, each of whose flows is an exact
//   rotation about one principal axis by angle t L_i / J_i, composed symmetrically as
//   R1(h/2) R2(h/2) R3(h) R2(h/2) R1(h/2). World L is never touched: conserved exactly.
//   The body-frame momentum turns the other way inside the composition, tracked with 2D
//   rotations (one cos and sin per sub-rotation; a polynomial for the usual small angles).
// - splitting4: the triple jump S(g1 h) S(g2 h) S(g1 h), g1 = 1/(2 - 2^(1/3)),
//   g2 = -2^(1/3) g1 (Yoshida, Phys. Lett. A 150 (1990)): 4th order.
// - free-rotor: the exact torque-free flow in the middle (Celledoni, Fasso, Safstrom, Zanna,
//   SIAM J. Sci. Comput. 30 (2008)): exact for free bodies, 2nd order with torques.
// The kick is exact: with x and q frozen, forces that depend on x and q only (gravity,
// constant torques, undamped springs) are constant, so v += a h/2, L += tau h/2 is their flow;
// with spring damping the kick is a linear ODE in (v, L), whose exact flow damped_kick()
// takes (damped_kick.cpp). Every sub-flow is then symmetric and each method keeps its order.
#include <cmath>
#include <optional>

#include "compensated_orientation.hpp"
#include "damped_kick.hpp"
#include "engine/exact/torque_free_exact.hpp"
#include "steppers.hpp"

namespace tumble::engine::steppers {
namespace {

/// Free rotation by the symmetric splitting R1(h/2) R2(h/2) R3(h) R2(h/2) R1(h/2). The five
/// turns are composed as one small turn, added to the compensated `orientation`, so the
/// rounding of a step is relative to the turn (compensated_orientation.hpp).
void split_rotation(const Eigen::Vector3d& inverse_moments, CompensatedOrientation& orientation,
                    BodyState& s, double h) {
  Eigen::Vector3d momentum = s.orientation.conjugate() * s.angular_momentum;  // body frame
  Eigen::Quaterniond turn(0.0, 0.0, 0.0, 0.0);  // small part of the composed turn
  const auto rotate_about = [&](int axis, double t) {
    // Body turns by +angle about the axis; its body-frame momentum by -angle.
    const double half = 0.5 * t * momentum[axis] * inverse_moments[axis];
    const HalfAngle f = half_angle(half * half);
    const double c = f.cos, sn = half * f.sinc;
    // turn <- small part of (1 + turn)(1 + d), d = (cos - 1, sn e_axis): compose_small
    // written out for an axis turn (8 products). With a, b the next axes (cyclic),
    // w' = w + d_w + w d_w - sn t_axis, t_axis' = t_axis + sn + d_w t_axis + w sn,
    // t_a' = t_a + d_w t_a + sn t_b, t_b' = t_b + d_w t_b - sn t_a.
    const int a = (axis + 1) % 3, b = (axis + 2) % 3;
    const double dw = f.cos_minus_one;
    const double w = turn.w(), ti = turn.vec()[axis], ta = turn.vec()[a], tb = turn.vec()[b];
    turn.w() = (w + dw) + (w * dw - sn * ti);
    turn.vec()[axis] = (ti + sn) + (dw * ti + w * sn);
    turn.vec()[a] = ta + (dw * ta + sn * tb);
    turn.vec()[b] = tb + (dw * tb - sn * ta);
    // The momentum turns by the full angle in the (a, b) plane.
    const double cos_full = c * c - sn * sn, sin_full = 2.0 * sn * c;
    const double ma = momentum[a], mb = momentum[b];
    momentum[a] = cos_full * ma + sin_full * mb;
    momentum[b] = -sin_full * ma + cos_full * mb;
  };
  rotate_about(0, 0.5 * h);
  rotate_about(1, 0.5 * h);
  rotate_about(2, h);
  rotate_about(1, 0.5 * h);
  rotate_about(0, 0.5 * h);
  orientation.resume(s.orientation);
  orientation.turn_body(turn);
  s.orientation = orientation.value();
}

class Splitting final : public BodyStepper {
 public:
  Splitting(const BodyModel& body, int order)
      : body_(body),
        inverse_moments_(body.moments.cwiseInverse()),
        order_(order),
        damped_(has_damping(body)) {}
  void step(BodyState& s, double, double h) override {
    if (order_ == 2) {
      second_order(s, h);
      return;
    }
    // Yoshida's triple jump.
    const double cube_root_two = std::cbrt(2.0);
    const double outer = 1.0 / (2.0 - cube_root_two);
    const double inner = -cube_root_two * outer;
    if (damped_) {
      // Neighbouring kicks act at the same x and q, so their exact flows merge,
      // exp(a M) exp(b M) = exp((a + b) M): four kicks instead of six.
      kick(body_, s, 0.5 * outer * h, &kick_flow_);
      drift(s, outer * h);
      kick(body_, s, 0.5 * (outer + inner) * h, &kick_flow_);
      drift(s, inner * h);
      kick(body_, s, 0.5 * (inner + outer) * h, &kick_flow_);
      drift(s, outer * h);
      kick(body_, s, 0.5 * outer * h, &kick_flow_);
      return;
    }
    second_order(s, outer * h);
    second_order(s, inner * h);
    second_order(s, outer * h);
  }

 private:
  void second_order(BodyState& s, double h) {
    KickFlowCache* damped = damped_ ? &kick_flow_ : nullptr;
    kick(body_, s, 0.5 * h, damped);
    drift(s, h);
    kick(body_, s, 0.5 * h, damped);
  }
  /// The free motion: x along v, the split free rotation.
  void drift(BodyState& s, double h) {
    if (!body_.pivoted) s.position += h * s.velocity;
    split_rotation(inverse_moments_, orientation_, s, h);
  }

  const BodyModel& body_;
  Eigen::Vector3d inverse_moments_;
  int order_;
  bool damped_;
  KickFlowCache kick_flow_;
  CompensatedOrientation orientation_;
};

class FreeRotor final : public BodyStepper {
 public:
  explicit FreeRotor(const BodyModel& body) : body_(body), damped_(has_damping(body)) {}
  void step(BodyState& s, double, double h) override {
    KickFlowCache* damped = damped_ ? &kick_flow_ : nullptr;
    kick(body_, s, 0.5 * h, damped);
    if (!body_.pivoted) s.position += h * s.velocity;
    free_flow(s, h);
    kick(body_, s, 0.5 * h, damped);
  }

 private:
  /// The exact torque-free flow from `s` over h; world L is constant along it. Built afresh
  /// from `s` when the kick changed L or the state is not the one the last step returned.
  /// Otherwise `s` is still on the motion the last step followed, and that motion is
  /// continued at the time elapsed since it was built (summed with compensation, so to
  /// rounding of the total): re-deriving it from the rounded state instead fed an error of
  /// ~1e-16 into its energy every step, a random walk that near the separatrix moves the
  /// flips (engine/PHYSICS.md §3).
  void free_flow(BodyState& s, double h) {
    if (!motion_ || s.orientation.coeffs() != end_orientation_.coeffs() ||
        s.angular_momentum != flow_momentum_) {
      const Eigen::Vector3d omega_body =
          (s.orientation.conjugate() * s.angular_momentum).cwiseQuotient(body_.moments);
      motion_.emplace(body_.moments, s.orientation, omega_body);
      flow_momentum_ = s.angular_momentum;
      elapsed_ = 0.0;
      elapsed_error_ = 0.0;
    }
    // Kahan's compensated sum of the steps.
    const double increment = h + elapsed_error_;
    const double sum = elapsed_ + increment;
    elapsed_error_ = increment - (sum - elapsed_);
    elapsed_ = sum;
    end_orientation_ = motion_->at(elapsed_).orientation;
    s.orientation = end_orientation_;
  }

  const BodyModel& body_;
  bool damped_;
  KickFlowCache kick_flow_;
  std::optional<TorqueFreeMotion> motion_;
  Eigen::Vector3d flow_momentum_ = Eigen::Vector3d::Zero();  // world L motion_ was built from
  double elapsed_ = 0.0;                                     // time since motion_ was built
  double elapsed_error_ = 0.0;                               // what rounding left out of elapsed_
  Eigen::Quaterniond end_orientation_ = Eigen::Quaterniond::Identity();
};

}  // namespace

std::unique_ptr<BodyStepper> make_splitting(const BodyModel& body, int order) {
  return std::make_unique<Splitting>(body, order);
}
std::unique_ptr<BodyStepper> make_free_rotor(const BodyModel& body) {
  return std::make_unique<FreeRotor>(body);
}

}  // namespace tumble::engine::steppers
