// moser-veselov: the discrete Moser-Veselov algorithm for the free rotation, forces and
// torques by kicks (half kick, drift, DMV step, half kick, as free-rotor).
//
// Moser and Veselov, "Discrete versions of some classical integrable systems and
// factorization of matrix polynomials", Commun. Math. Phys. 139 (1991): the discrete
// Lagrangian tr(Omega J) / h on the relative rotation Omega = R_n^T R_{n+1}, with the
// "mass matrix" J = tr(I)/2 - I, gives the body-frame momentum map
//   h M_n = Omega J - J Omega^T,   M_{n+1} = Omega^T M_n Omega,   R_{n+1} = R_n Omega
// (M the skew matrix of the body momentum m). McLachlan and Zanna, "The discrete
// Moser-Veselov algorithm for the free rigid body, revisited", Found. Comput. Math. 5 (2005),
// write it with the quaternion (w, v) of Omega, and analyse it as the exact flow of a modified
// (time-reparametrised) rigid body: second order as an approximation of the true flow at the
// same step. This is the plain algorithm, without their preprocessing of the initial data.
//
// With Omega = (w^2 - v.v) 1 + 2 v v^T + 2 w [v]x, the first equation reads
//   2 w I v + 2 v x I v = h m
// (the symmetric parts cancel, [v]x J + J [v]x = [(tr J - J) v]x = [I v]x and
// (J v) x v = v x (I v)), so J itself is never needed (it may be singular for flat bodies).
// In the Gibbs vector u = v / w (|w| = 1 / sqrt(1 + u.u)) it becomes the quadratic
//   F(u) = 2 (I u + u x I u) - h m (1 + u.u) = 0,
// solved by Newton from u = h I^-1 m / 2 (which selects the solution near the identity).
// World L = R_n m_n = R_n Omega Omega^T m_n is the same before and after: it is not touched.
// The free body's energy m.I^-1 m / 2 and |m| are integrals of the discrete map: kept to
// rounding (measured in tests/engine/moser_veselov_test.cpp).
#include <cmath>
#include <limits>

#include <Eigen/LU>

#include "damped_kick.hpp"
#include "steppers.hpp"

namespace tumble::engine::steppers {
namespace {

/// The relative rotation Omega of one DMV step from body momentum `m`, as a unit quaternion;
/// NaN when Newton does not converge (a step far too long for the spin).
Eigen::Quaterniond dmv_rotation(const Eigen::Vector3d& moments, const Eigen::Vector3d& m,
                                double h) {
  const Eigen::Vector3d hm = h * m;
  Eigen::Vector3d u = 0.5 * hm.cwiseQuotient(moments);
  double last_change = 0.0;
  for (int iteration = 0; iteration < 30; ++iteration) {
    const Eigen::Vector3d Iu = moments.cwiseProduct(u);
    const Eigen::Vector3d f = 2.0 * (Iu + u.cross(Iu)) - (1.0 + u.squaredNorm()) * hm;
    const Eigen::Matrix3d jacobian =
        2.0 * (Eigen::Matrix3d(moments.asDiagonal()) + cross_matrix(u) * moments.asDiagonal() -
               cross_matrix(Iu)) -
        2.0 * hm * u.transpose();
    const Eigen::Vector3d delta = jacobian.partialPivLu().solve(f);
    u -= delta;
    last_change = delta.norm();
    if (!(last_change > 1e-15 * u.norm())) break;  // at rounding (or u = 0 at rest)
  }
  // Quadratic convergence reaches rounding in a few iterations; a change still above 1e-10 of
  // u after 30 means no nearby solution.
  if (!(last_change <= 1e-10 * u.norm() || last_change == 0.0) || !u.allFinite()) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    return Eigen::Quaterniond(nan, nan, nan, nan);
  }
  const double w = 1.0 / std::sqrt(1.0 + u.squaredNorm());
  return Eigen::Quaterniond(w, w * u.x(), w * u.y(), w * u.z());
}

class MoserVeselov final : public BodyStepper {
 public:
  explicit MoserVeselov(const BodyModel& body) : body_(body), damped_(has_damping(body)) {}
  void step(BodyState& s, double, double h) override {
    KickFlowCache* damped = damped_ ? &kick_flow_ : nullptr;
    kick(body_, s, 0.5 * h, damped);
    if (!body_.pivoted) s.position += h * s.velocity;
    const Eigen::Vector3d m = s.orientation.conjugate() * s.angular_momentum;  // body frame
    // R_{n+1} = R_n Omega; the body momentum R_{n+1}^T L is then Omega^T m_n.
    s.orientation = renormalized(s.orientation * dmv_rotation(body_.moments, m, h));
    kick(body_, s, 0.5 * h, damped);
  }

 private:
  const BodyModel& body_;
  bool damped_;
  KickFlowCache kick_flow_;
};

}  // namespace

std::unique_ptr<BodyStepper> make_moser_veselov(const BodyModel& body) {
  return std::make_unique<MoserVeselov>(body);
}

}  // namespace tumble::engine::steppers
