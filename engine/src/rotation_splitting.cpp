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
// Velocity-dependent forces (spring damping) are kicked explicitly, which makes those terms
// first order; everything conservative keeps the stated order.
#include <cmath>

#include "engine/torque_free_exact.hpp"
#include "steppers.hpp"

namespace tumble::engine::steppers {
namespace {

/// Half kick: v and world L from the forces and torques at `s`.
void kick(const BodyModel& body, BodyState& s, double half_step) {
  if (body.forces.empty()) return;
  const Rates r = rates(body, s);
  s.velocity += half_step * r.acceleration;
  s.angular_momentum += half_step * r.torque;
}

/// Free rotation by the symmetric splitting R1(h/2) R2(h/2) R3(h) R2(h/2) R1(h/2).
void split_rotation(const Eigen::Vector3d& inverse_moments, BodyState& s, double h) {
  Eigen::Vector3d momentum = s.orientation.conjugate() * s.angular_momentum;  // body frame
  Eigen::Vector4d q(s.orientation.w(), s.orientation.x(), s.orientation.y(), s.orientation.z());
  const auto rotate_about = [&](int axis, double t) {
    // Body turns by +angle about the axis; its body-frame momentum by -angle.
    const double half = 0.5 * t * momentum[axis] * inverse_moments[axis];
    const HalfAngle f = half_angle(half * half);
    const double c = f.cos, sn = half * f.sinc;
    // q <- q (c, sn e_axis): with a, b the next axes, w' = c w - sn q_axis,
    // q_axis' = c q_axis + sn w, q_a' = c q_a + sn q_b, q_b' = c q_b - sn q_a (8 products).
    const int i = axis + 1, a = (axis + 1) % 3, b = (axis + 2) % 3;
    const double w = q[0], qi = q[i], qa = q[a + 1], qb = q[b + 1];
    q[0] = c * w - sn * qi;
    q[i] = c * qi + sn * w;
    q[a + 1] = c * qa + sn * qb;
    q[b + 1] = c * qb - sn * qa;
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
  s.orientation = renormalized(Eigen::Quaterniond(q[0], q[1], q[2], q[3]));
}

class Splitting final : public BodyStepper {
 public:
  Splitting(const BodyModel& body, int order)
      : body_(body), inverse_moments_(body.moments.cwiseInverse()), order_(order) {}
  void step(BodyState& s, double, double h) override {
    if (order_ == 2) {
      second_order(s, h);
      return;
    }
    // Yoshida's triple jump.
    const double cube_root_two = std::cbrt(2.0);
    const double outer = 1.0 / (2.0 - cube_root_two);
    const double inner = -cube_root_two * outer;
    second_order(s, outer * h);
    second_order(s, inner * h);
    second_order(s, outer * h);
  }

 private:
  void second_order(BodyState& s, double h) const {
    kick(body_, s, 0.5 * h);
    if (!body_.pivoted) s.position += h * s.velocity;
    split_rotation(inverse_moments_, s, h);
    kick(body_, s, 0.5 * h);
  }

  const BodyModel& body_;
  Eigen::Vector3d inverse_moments_;
  int order_;
};

class FreeRotor final : public BodyStepper {
 public:
  explicit FreeRotor(const BodyModel& body) : body_(body) {}
  void step(BodyState& s, double, double h) override {
    kick(body_, s, 0.5 * h);
    if (!body_.pivoted) s.position += h * s.velocity;
    const Eigen::Vector3d omega_body =
        (s.orientation.conjugate() * s.angular_momentum).cwiseQuotient(body_.moments);
    const TorqueFreeMotion flow(body_.moments, s.orientation, omega_body);
    s.orientation = flow.at(h).orientation;  // world L is constant along the flow
    kick(body_, s, 0.5 * h);
  }

 private:
  const BodyModel& body_;
};

}  // namespace

std::unique_ptr<BodyStepper> make_splitting(const BodyModel& body, int order) {
  return std::make_unique<Splitting>(body, order);
}
std::unique_ptr<BodyStepper> make_free_rotor(const BodyModel& body) {
  return std::make_unique<FreeRotor>(body);
}

}  // namespace tumble::engine::steppers
