// Exact torque-free motion of a rigid body.
//
// Design note. Euler's equations without torque conserve the energy 2T = sum I_i w_i^2 and
// G^2 = |I w|^2; their solution is (Landau & Lifshitz, Mechanics, §37; engine/PHYSICS.md §4)
//   w = (s1 A1 cn u, s2 A2 sn u, A3 dn u),  u = u0 + lambda t,
// in a principal frame labelled J1, J2, J3 with J2 the intermediate moment and J3 the moment
// of the axis that omega circles (J3 the largest when G^2 > 2T I2, the smallest otherwise;
// every formula below is written so it holds for both orders). With
//   a = 2T J3 - G^2,  b = G^2 - 2T J1,  d = G^2 - 2T J2,
// each expanded as a sum over w_i^2 so that no large terms cancel,
//   A1^2 = a / (J1 (J3 - J1)),  A2^2 = a / (J2 (J3 - J2)),  A3^2 = b / (J3 (J3 - J1)),
//   lambda^2 = (J3 - J2) b / (J1 J2 J3),  m = (J2 - J1) a / ((J3 - J2) b),
//   1 - m = (J3 - J1) d / ((J3 - J2) b)   (computed directly: m -> 1 at the separatrix).
//
// Orientation. World L is constant. In an auxiliary world frame with z along L the body
// orientation is Rz(phi) Rx(theta) Rz(psi) (z-x-z Euler angles), where the body components
// of L/G = (sin theta sin psi, sin theta cos psi, cos theta) give theta and psi directly, and
//   dphi/dt = G (J1 w1^2 + J2 w2^2) / (J1^2 w1^2 + J2^2 w2^2)
//           = G/J3 + C / (1 - n sn^2 u),  C = G (J3 - J1) / (J1 J3),
//   n = -J3 (J2 - J1) / (J1 (J3 - J2))  (n <= 0: the integrand has no pole),
// so phi(t) = G t / J3 + (C / lambda) Pi~(u) + const with Pi~(u) = int_0^u du / (1 - n sn^2)
// = Pi(n; am u | m), evaluated for |u| <= K as u + (n/3) sn^3 R_J(cn^2, dn^2, 1, 1 - n sn^2)
// (DLMF 19.25.14 with F(am u) = u). For long times u is reduced by the half period 2K:
// Pi~(u + 2K) = Pi~(u) + 2 Pi(n|m), so phi gains a fixed Phi_half per half period, and the
// state at any time costs one sn/cn/dn and one R_J. The auxiliary frame is anchored on the
// state at t = 0, so the constant in phi never has to be computed; keeping w3 > 0 (a proper
// re-labelling) keeps theta in [0, pi/2) where the Euler angles are well conditioned; psi is
// unwrapped across half periods so the quaternion is continuous in t. Cf. Celledoni, Fasso,
// Safstrom, Zanna (2008), SIAM J. Sci. Comput. 30(4), which uses theta functions for the same
// integral.
//
// Units: internally omega and the moments are scaled by powers of two to magnitudes near 1 (the
// motion is homogeneous in both, and the scaling is exact), so extreme magnitudes neither
// overflow nor underflow.
#include "engine/exact/torque_free_exact.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "engine/exact/elliptic.hpp"

#include "exact_numbers.hpp"

namespace tumble::engine {
namespace {

using exact_numbers::kInf;
using exact_numbers::kNaN;
using exact_numbers::kPi;
// |w x I w| / (|w| |I w|) below which omega is taken to lie on a principal axis. The true
// motion differs from a permanent rotation by an angle of this order (times an exponential
// growth of e^(lambda t) about the intermediate axis), far below anything measurable.
constexpr double kPermanentTolerance = 1e-100;

// Quaternion of Rz(phi) Rx(theta) Rz(psi) from cos(theta/2), sin(theta/2).
Eigen::Quaterniond euler_zxz(double phi, double cos_half, double sin_half, double psi) {
  const double alpha = 0.5 * (phi + psi);
  const double beta = 0.5 * (phi - psi);
  return {cos_half * std::cos(alpha), sin_half * std::cos(beta), sin_half * std::sin(beta),
          cos_half * std::sin(alpha)};
}

}  // namespace

TorqueFreeMotion::TorqueFreeMotion(const Eigen::Vector3d& moments,
                                   const Eigen::Quaterniond& orientation,
                                   const Eigen::Vector3d& omega_body) {
  // Moments are body constants: refuse bad ones here, at creation.
  if (!moments.allFinite() || (moments.array() <= 0.0).any()) {
    std::ostringstream message;
    message << "TorqueFreeMotion: principal moments must be finite and positive, got ("
            << moments.x() << ", " << moments.y() << ", " << moments.z() << ")";
    throw std::invalid_argument(message.str());
  }
  // A non-finite state propagates as NaN instead of throwing.
  if (!omega_body.allFinite() || !orientation.coeffs().allFinite() ||
      orientation.coeffs().squaredNorm() == 0.0) {
    regime_ = Regime::kInvalid;
    energy_ = kNaN;
    angular_momentum_world_.setConstant(kNaN);
    return;
  }
  orientation0_ = orientation.normalized();
  omega0_ = omega_body;
  const Eigen::Vector3d momentum_body = moments.cwiseProduct(omega_body);
  energy_ = 0.5 * omega_body.dot(momentum_body);
  angular_momentum_world_ = orientation0_ * momentum_body;

  // Trivial motions: rest, a sphere, a spin about a principal axis.
  const double omega_max = omega_body.cwiseAbs().maxCoeff();
  if (omega_max == 0.0) {
    regime_ = Regime::kAtRest;
    return;
  }
  // Scale by powers of two (exact: an exact separatrix stays exact).
  scale_ = std::ldexp(1.0, std::ilogb(omega_max));
  const Eigen::Vector3d w = omega_body / scale_;
  const Eigen::Vector3d jn = moments / std::ldexp(1.0, std::ilogb(moments.maxCoeff()));
  const Eigen::Vector3d lw = jn.cwiseProduct(w);
  if (jn.minCoeff() == jn.maxCoeff() ||
      w.cross(lw).norm() <= kPermanentTolerance * w.norm() * lw.norm()) {
    regime_ = Regime::kPermanentRotation;
    return;
  }

  const InternalStart start = enter_internal_frame(jn, w);  // axes sorted and signed
  if (!solve_elliptic(start)) {                             // amplitudes, rate, parameter
    regime_ = Regime::kPermanentRotation;
    return;
  }
  set_initial_argument(start.omega);  // signs and u0
  set_half_period();                  // K and the precession per half period

  // Anchor the auxiliary frame at the state at t = 0 computed through the same path at() uses:
  // at(0) then returns the initial orientation to rounding, and phi(0) cancels out.
  const Local local0 = local(0.0);
  prefix_ = orientation0_ * to_internal_q_.conjugate() * local0.euler.conjugate();
}

TorqueFreeMotion::InternalStart TorqueFreeMotion::enter_internal_frame(const Eigen::Vector3d& jn,
                                                                       const Eigen::Vector3d& w) {
  // Sort the axes and pick the circled axis from the sign of d = G^2 - 2T I2.
  std::array<int, 3> order{0, 1, 2};
  std::stable_sort(order.begin(), order.end(), [&](int x, int y) { return jn[x] < jn[y]; });
  const int lo = order[0];
  const int mid = order[1];
  const int hi = order[2];
  const double d_sorted =
      jn[lo] * (jn[lo] - jn[mid]) * w[lo] * w[lo] + jn[hi] * (jn[hi] - jn[mid]) * w[hi] * w[hi];
  const bool about_largest = d_sorted >= 0.0;
  const std::array<int, 3> axis =
      about_largest ? std::array<int, 3>{lo, mid, hi} : std::array<int, 3>{hi, mid, lo};

  // Proper signed permutation to the internal frame, with w3 > 0.
  Eigen::Matrix3d p = Eigen::Matrix3d::Zero();
  for (int k = 0; k < 3; ++k) p(k, axis[k]) = 1.0;
  if (p.determinant() < 0.0) p.row(0) *= -1.0;
  Eigen::Vector3d wi = p * w;
  if (wi.z() < 0.0) {
    p.row(0) *= -1.0;
    p.row(2) *= -1.0;
    wi = p * w;
  }
  to_internal_ = p;
  to_internal_q_ = Eigen::Quaterniond(p);
  j_ = Eigen::Vector3d(jn[axis[0]], jn[axis[1]], jn[axis[2]]);
  return {wi, about_largest};
}

bool TorqueFreeMotion::solve_elliptic(const InternalStart& start) {
  const double j1 = j_.x();
  const double j2 = j_.y();
  const double j3 = j_.z();
  const double w1 = start.omega.x();
  const double w2 = start.omega.y();
  const double w3 = start.omega.z();

  // Invariant combinations as sums of same-signed terms.
  const double a = j1 * (j3 - j1) * w1 * w1 + j2 * (j3 - j2) * w2 * w2;
  const double b = j2 * (j2 - j1) * w2 * w2 + j3 * (j3 - j1) * w3 * w3;
  const double d = j1 * (j1 - j2) * w1 * w1 + j3 * (j3 - j2) * w3 * w3;
  if (a == 0.0 || b == 0.0) return false;

  // Amplitudes, rate, parameter (engine/PHYSICS.md §4, L&L §37).
  amplitude_ = Eigen::Vector3d(std::sqrt(a / (j1 * (j3 - j1))), std::sqrt(a / (j2 * (j3 - j2))),
                               std::sqrt(b / (j3 * (j3 - j1))));
  lambda_ = std::sqrt((j3 - j2) * b / (j1 * j2 * j3));
  m_ = std::clamp((j2 - j1) * a / ((j3 - j2) * b), 0.0, 1.0);
  m1_ = std::clamp((j3 - j1) * d / ((j3 - j2) * b), 0.0, 1.0);
  if (m1_ == 0.0) m_ = 1.0;
  regime_ = m1_ == 0.0
                ? Regime::kSeparatrix
                : (start.about_largest ? Regime::kAboutLargestAxis : Regime::kAboutSmallestAxis);
  n_ = -j3 * (j2 - j1) / (j1 * (j3 - j2));
  g_ = j_.cwiseProduct(start.omega).norm();
  c_ = g_ * (j3 - j1) / (j1 * j3);
  return true;
}

void TorqueFreeMotion::set_initial_argument(const Eigen::Vector3d& wi) {
  // Signs: s1 from w1; Euler's equations then fix s2 = s1 sign(J3 - J1) (w3 > 0 here).
  s1_ = wi.x() >= 0.0 ? 1.0 : -1.0;
  s2_ = j_.z() > j_.x() ? s1_ : -s1_;

  // Initial argument u0 in [-K, K] from cn(u0) = |w1| / A1 >= 0, sn(u0) = s2 w2 / A2.
  double cn0 = std::abs(wi.x()) / amplitude_.x();
  double sn0 = s2_ * wi.y() / amplitude_.y();
  const double r0 = std::hypot(cn0, sn0);
  cn0 /= r0;
  sn0 /= r0;
  u0_ = sn0 * carlson_rf(cn0 * cn0, cn0 * cn0 + m1_ * sn0 * sn0, 1.0);
}

void TorqueFreeMotion::set_half_period() {
  // Quarter period and the precession gained per half period.
  parameter_ = elliptic_parameter(m_, m1_);
  k_ = parameter_.quarter;
  if (std::isfinite(k_)) {
    const double pi_complete = n_ == 0.0 ? k_ : k_ + n_ / 3.0 * carlson_rj(0.0, m1_, 1.0, 1.0 - n_);
    phi_half_ = 2.0 / lambda_ * (g_ * k_ / j_.z() + c_ * pi_complete);
    phi_half_mod_ = std::remainder(phi_half_, 4.0 * kPi);
  }
}

double TorqueFreeMotion::pi_tilde(double u_reduced, double sn, double cn, double dn) const {
  if (n_ == 0.0) return u_reduced;
  if (m1_ == 0.0) {
    // Separatrix: int du / (1 + N tanh^2 u) = (u + sqrt(N) atan(sqrt(N) tanh u)) / (1 + N).
    const double big_n = -n_;
    const double root = std::sqrt(big_n);
    return (u_reduced + root * std::atan(root * sn)) / (1.0 + big_n);
  }
  const double sn2 = sn * sn;
  return u_reduced + n_ / 3.0 * sn * sn2 * carlson_rj(cn * cn, dn * dn, 1.0, 1.0 - n_ * sn2);
}

TorqueFreeMotion::Local TorqueFreeMotion::local(double tau) const {
  // Reduce u = u0 + lambda tau to u_r in [-K, K] plus j half periods.
  const double u = u0_ + lambda_ * tau;
  double j = 0.0;
  double ur = u;
  if (std::isfinite(k_)) {
    j = std::nearbyint(u / (2.0 * k_));
    if (j != 0.0) ur = u - j * (2.0 * k_);
  }
  const JacobiElliptic e = jacobi_elliptic(ur, parameter_);
  const double sn = e.sn;
  const double cn = std::abs(e.cn);
  const double dn = e.dn;
  const double parity = std::fmod(j, 2.0) != 0.0 ? -1.0 : 1.0;

  Local out;
  out.omega = Eigen::Vector3d(s1_ * amplitude_.x() * parity * cn,
                              s2_ * amplitude_.y() * parity * sn, amplitude_.z() * dn);

  // Nutation and spin from L in body axes; psi unwrapped by -s1 s2 pi per half period.
  const double x = j_.x() * amplitude_.x() * cn;
  const double y = s2_ * j_.y() * amplitude_.y() * sn;
  const double z = j_.z() * amplitude_.z() * dn;
  const double rho = std::hypot(x, y);
  const double r = std::hypot(rho, z);
  const double psi = s1_ * std::atan2(x, y) - s1_ * s2_ * kPi * std::fmod(j, 4.0);
  const double cos_half = std::sqrt(0.5 * (1.0 + z / r));
  const double sin_half = 0.5 * rho / (r * cos_half);

  // Precession angle: whole half periods plus the reduced part.
  double phi = 0.0;
  const double pt = pi_tilde(ur, sn, cn, dn);
  if (j == 0.0) {
    phi = g_ / j_.z() * tau + c_ / lambda_ * pt;
  } else {
    phi = std::remainder(j * phi_half_mod_, 4.0 * kPi) + g_ / j_.z() * (ur - u0_) / lambda_ +
          c_ / lambda_ * pt;
  }
  out.euler = euler_zxz(phi, cos_half, sin_half, psi);
  return out;
}

TorqueFreeMotion::State TorqueFreeMotion::at(double t) const {
  switch (regime_) {
    case Regime::kInvalid:
      return {Eigen::Quaterniond(kNaN, kNaN, kNaN, kNaN), Eigen::Vector3d::Constant(kNaN)};
    case Regime::kAtRest:
      return {orientation0_, omega0_};
    case Regime::kPermanentRotation: {
      // q(t) = q0 exp(t w / 2) with w fixed in the body.
      const double speed = omega0_.stableNorm();
      const double half = 0.5 * speed * t;
      const Eigen::Vector3d v = std::sin(half) / speed * omega0_;
      const Eigen::Quaterniond turn(std::cos(half), v.x(), v.y(), v.z());
      return {(orientation0_ * turn).normalized(), omega0_};
    }
    default:
      break;
  }
  const Local l = local(scale_ * t);
  Eigen::Quaterniond q = prefix_ * l.euler * to_internal_q_;
  q.normalize();
  return {q, scale_ * (to_internal_.transpose() * l.omega)};
}

double TorqueFreeMotion::omega_period() const {
  if (regime_ != Regime::kAboutLargestAxis && regime_ != Regime::kAboutSmallestAxis) return kInf;
  return 4.0 * k_ / (lambda_ * scale_);
}

double TorqueFreeMotion::flip_interval() const {
  if (m_ == 0.0) return kInf;
  return 0.5 * omega_period();
}

double TorqueFreeMotion::precession_per_period() const {
  if (!std::isfinite(omega_period())) return kNaN;
  return 2.0 * phi_half_;
}

}  // namespace tumble::engine
