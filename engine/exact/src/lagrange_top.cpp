// Exact motion of the heavy symmetric (Lagrange) top.
//
// Design note (engine/PHYSICS.md §4b). Goldstein, Classical Mechanics §5.7, and Landau and
// Lifshitz, Mechanics §35: a top with transverse moment I1 and axial moment I3 about its pivot,
// centre of mass a distance l up its axis, in uniform gravity g, keeps its energy, the axial
// momentum L3 = L . a (a the unit axis) and the vertical momentum Lz = L . up. With
// u = cos(tilt) = a . up, b = Lz / I1, a = L3 / I1, beta = 2 m g l / I1,
//   du/dt^2 = f(u) = (1 - u^2)(alpha - beta u) - (b - a u)^2,
// a cubic with f(+-1) = -(b -+ a)^2 <= 0, so its roots are -1 <= u1 <= u2 <= 1 <= u3 and
//   u = u1 + (u2 - u1) sn^2(tau | m),  tau = tau0 + lambda t,
//   lambda^2 = beta (u3 - u1) / 4,  m = (u2 - u1) / (u3 - u1),  1 - m = (u3 - u2) / (u3 - u1).
// Everything is written about the initial u0: with x = u - u0 the cubic is
//   f = f0 + f1 x + f2 x^2 + beta x^3,  f0 = (du/dt)^2, f1 = -beta (1 - u0^2) - 2 u0 K0 + 2 a P0,
//   f2 = 2 beta u0 - K0 - a^2,  K0 = |w_perp|^2 = alpha - beta u0,  P0 = up . w_perp = b - a u0,
// each from the state directly (no energy subtraction), and 1 -+ u0 come from |a -+ up|^2 / 2,
// so the roots near u0 keep their relative accuracy; the third root comes from a product of
// the roots, and the distances to the poles 1 + u1, 1 - u2 from f(-1) = -(b + a)^2 and
// f(1) = -(b - a)^2 (b +- a = L . (up +- a) / I1), which keep theirs near a pole.
//
// Angles. z-x-z Euler angles phi (precession), theta, psi (spin) about the vertical:
// dphi/dt = (b - a u) / (1 - u^2), dpsi/dt = L3 / I3 - u dphi/dt. Rather than phi and psi, which
// are singular where the axis is vertical, the code integrates Sigma = phi + psi and
// Delta = phi - psi, which enter the quaternion as
//   (cos(theta/2) cos(Sigma/2), sin(theta/2) cos(Delta/2), sin(theta/2) sin(Delta/2),
//    cos(theta/2) sin(Sigma/2))
// and whose rates have one pole each (the partial fractions of dphi/dt):
//   dSigma/dt = (L3/I3 - a) + (b + a) / (1 + u),   dDelta/dt = (a - L3/I3) + (b - a) / (1 - u).
// With 1 + u = (1 + u1)(1 - n- sn^2), n- = -(u2 - u1) / (1 + u1) <= 0, and
// 1 - u = (1 - u1)(1 - n+ sn^2), n+ = (u2 - u1) / (1 - u1) in [0, 1), each integral is
// rate t + c Pi(n; am tau | m) with Pi evaluated, for |tau| <= K, as
// tau + (n/3) sn^3 R_J(cn^2, dn^2, 1, 1 - n sn^2) (DLMF 19.25.14; as in §4), 1 - n sn^2 taken
// as (1 -+ u) / (1 -+ u1), and through the dual characteristic m / n when n < -1 (near straight
// down, where that form cancels: see third_kind). A top whose axis
// passes through the vertical (u2 = 1, so b = a) has no pole in Delta: the term is dropped and
// sin(theta/2) = sqrt((u2 - u1)/2) cn, signed, keeps the quaternion smooth through it (the
// limit of the 2 pi turn of Delta of a near pass); likewise through straight down (u1 = -1).
// For the elliptic-integral form of the Euler angles of the Lagrange top see also Mingari
// Scarpello and Ritelli (2018), Celest. Mech. Dyn. Astron. 130.
//
// Long times: tau is reduced by the half period 2K, sn^2 has that period, and Sigma, Delta gain
// a fixed amount per half period, reduced modulo 4 pi: any time costs one sn/cn/dn and two R_J.
// The vertical frame is anchored on the state at t = 0 computed through the same path, so no
// integration constant is needed and at(0) returns the initial orientation to rounding.
// World L follows from the quaternion's derivative: L = L3 a + I1 w_perp.
#include "engine/exact/lagrange_top.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <variant>

#include "base/errors.hpp"

#include "exact_numbers.hpp"

namespace tumble::engine {
namespace {

using exact_numbers::kInf;
using exact_numbers::kNaN;
using exact_numbers::kPi;

/// Pi(n; am tau | m) for |tau| <= K, with p = 1 - n sn^2 given by the caller: near n = 1 (a pass
/// close to the vertical) it is computed as (1 - u) / (1 - u1), since 1 - n itself has lost its
/// digits there. For n >= -1, tau + (n/3) sn^3 R_J(cn^2, dn^2, 1, p) (DLMF 19.25.14). For
/// n < -1 (a pass close to straight down: n -> -inf) the two terms of that form cancel to
/// Pi ~ 1/sqrt(-n), so the transformation n -> n' = m/n (DLMF 19.7.9) is used instead:
///   Pi(n) = tau - Pi(n') + sn R_C(cn^2 dn^2, p (1 - n' sn^2))
///         = -(n'/3) sn^3 R_J(cn^2, dn^2, 1, 1 - n' sn^2) + sn R_C(cn^2 dn^2, p (1 - n' sn^2)),
/// every term of one sign.
double third_kind(double n, double p, double tau_reduced, const JacobiElliptic& e, double m) {
  if (n == 0.0) return tau_reduced;
  const double sn = e.sn, cn = e.cn, dn = e.dn;
  const double sn3 = sn * sn * sn;
  if (n >= -1.0) return tau_reduced + n / 3.0 * sn3 * carlson_rj(cn * cn, dn * dn, 1.0, p);
  const double n_dual = m / n;
  const double p_dual = 1.0 - n_dual * sn * sn;
  const double dual =
      n_dual == 0.0 ? 0.0 : -n_dual / 3.0 * sn3 * carlson_rj(cn * cn, dn * dn, 1.0, p_dual);
  return dual + sn * carlson_rc(cn * cn * dn * dn, p * p_dual);
}

/// Pi(n|m), the same two ways: K + (n/3) R_J(0, 1 - m, 1, 1 - n), or for n < -1
/// -(n'/3) R_J(0, 1 - m, 1, 1 - n') + (pi/2) / sqrt((1 - n)(1 - n')), n' = m/n.
double third_kind_complete(double n, double one_minus_n, const EllipticParameter& parameter) {
  const double k = parameter.quarter;
  if (n == 0.0) return k;
  if (n >= -1.0) return k + n / 3.0 * carlson_rj(0.0, parameter.m1, 1.0, one_minus_n);
  const double n_dual = parameter.m / n;
  const double dual =
      n_dual == 0.0 ? 0.0 : -n_dual / 3.0 * carlson_rj(0.0, parameter.m1, 1.0, 1.0 - n_dual);
  return dual + 0.5 * kPi / std::sqrt(one_minus_n * (1.0 - n_dual));
}

Eigen::Vector3d total_gravity(const BodyModel& body) {
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  for (const ForceTerm& term : body.forces) {
    if (const auto* gravity = std::get_if<Gravity>(&term)) g += gravity->acceleration;
  }
  return g;
}

/// The principal axis the centre of mass lies on (the largest offset component).
int offset_axis(const BodyModel& body) {
  int axis = 0;
  body.center_offset.cwiseAbs().maxCoeff(&axis);
  return axis;
}

/// The root of the cubic c0 + c1 x + c2 x^2 + x^3 in [lo, hi] where it changes from positive
/// to not (`positive_left`) or from not positive to positive, by bisection to adjacent doubles
/// (a root exactly at an end is found exactly). Only run at construction: at most about a
/// thousand evaluations.
double bracketed_root(double c0, double c1, double c2, double lo, double hi, bool positive_left) {
  const auto f = [&](double x) { return c0 + x * (c1 + x * (c2 + x)); };
  for (int i = 0; i < 2200; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (!(mid > lo && mid < hi)) break;
    if ((f(mid) > 0.0) == positive_left) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  // The end nearer the sign change: lo holds the left side's sign, hi the other.
  return positive_left ? lo : hi;
}

}  // namespace

std::optional<std::string> lagrange_top_problem(const BodyModel& body) {
  if (!body.pivoted) return "it is not pivoted";
  for (const ForceTerm& term : body.forces) {
    if (!std::holds_alternative<Gravity>(term)) {
      return "it has a torque or a spring (a Lagrange top feels gravity only)";
    }
  }
  const Eigen::Vector3d g = total_gravity(body);
  const Eigen::Vector3d& c = body.center_offset;
  if (g.squaredNorm() == 0.0 || c.squaredNorm() == 0.0) return std::nullopt;  // no torque
  const int s = offset_axis(body);
  const int i = (s + 1) % 3, j = (s + 2) % 3;
  const double length = c.norm();
  if (std::abs(c[i]) > kLagrangeTopTolerance * length ||
      std::abs(c[j]) > kLagrangeTopTolerance * length) {
    return "its centre of mass is not on a principal axis through the pivot";
  }
  const double spread = std::abs(body.moments[i] - body.moments[j]);
  if (!(spread <= kLagrangeTopTolerance * body.moments.maxCoeff())) {
    return "the two principal moments across the axis of its centre of mass differ (not a "
           "symmetric top)";
  }
  return std::nullopt;
}

bool is_lagrange_top(const BodyModel& body) {
  return !lagrange_top_problem(body);
}

LagrangeTop::LagrangeTop(const BodyModel& body, const BodyState& initial)
    : body_(body), initial_(initial) {
  if (const auto problem = lagrange_top_problem(body)) {
    throw InputError("body '" + body.name + "' is not a Lagrange top: " + *problem);
  }
  update_pivot_kinematics(body_, initial_);
  const Eigen::Quaterniond q0 = initial.orientation.normalized();
  const Eigen::Vector3d& momentum = initial.angular_momentum;
  if (!q0.coeffs().allFinite() || !momentum.allFinite()) {
    regime_ = Regime::kInvalid;
    return;
  }
  const Eigen::Vector3d g = total_gravity(body);
  const Eigen::Vector3d& c = body.center_offset;
  if (g.squaredNorm() == 0.0 || c.squaredNorm() == 0.0) {
    regime_ = Regime::kTorqueFree;
    free_.emplace(body.moments, q0, (q0.conjugate() * momentum).cwiseQuotient(body.moments));
    return;
  }
  const int s = offset_axis(body);
  const int i = (s + 1) % 3, j = (s + 2) % 3;
  i1_ = 0.5 * (body.moments[i] + body.moments[j]);
  const double i3 = body.moments[s];
  const double l = std::abs(c[s]);
  const Eigen::Vector3d axis_body = (c[s] > 0.0 ? 1.0 : -1.0) * Eigen::Vector3d::Unit(s);
  const double g_norm = g.norm();
  const Eigen::Vector3d up = -g / g_norm;
  beta_ = 2.0 * body.mass * g_norm * l / i1_;

  const Eigen::Vector3d axis = q0 * axis_body;
  l3_ = momentum.dot(axis);
  rate_ = l3_ * (i1_ - i3) / (i1_ * i3);
  Eigen::Vector3d w_perp = (momentum - l3_ * axis) / i1_;
  w_perp -= w_perp.dot(axis) * axis;
  const double one_minus_u0 = 0.5 * (axis - up).squaredNorm();
  const double one_plus_u0 = 0.5 * (axis + up).squaredNorm();
  const double udot0 = up.dot(w_perp.cross(axis));
  bpa_ = momentum.dot(up + axis) / i1_;
  bma_ = momentum.dot(up - axis) / i1_;
  solve_roots(one_minus_u0, one_plus_u0, udot0, w_perp.squaredNorm(), up.dot(w_perp));
  set_nutation(udot0);
  set_precession();
  anchor(q0, axis, momentum);
}

void LagrangeTop::solve_roots(double one_minus_u0, double one_plus_u0, double udot0, double k0,
                              double p0) {
  // f(u0 + x) / beta = x^3 + c2 x^2 + c1 x + c0 (see the design note).
  const double u0 = 0.5 * (one_plus_u0 - one_minus_u0);
  const double a = l3_ / i1_;
  const double c0 = udot0 * udot0 / beta_;
  const double c1 = (-beta_ * one_minus_u0 * one_plus_u0 - 2.0 * u0 * k0 + 2.0 * a * p0) / beta_;
  const double c2 = (2.0 * beta_ * u0 - k0 - a * a) / beta_;
  // f >= 0 at x = 0, f <= 0 at u = -1 and u = 1: x1 in [-(1 + u0), 0], x2 in [0, 1 - u0].
  x1_ = bracketed_root(c0, c1, c2, -one_plus_u0, 0.0, false);
  x2_ = bracketed_root(c0, c1, c2, 0.0, one_minus_u0, true);
  // The third root (u3 >= 1) from a product of the roots, which keeps its relative accuracy
  // when all three lie close to u0 (a slow top just off the upright: u2, u3 -> 1), or from
  // their sum when both others are zero; then polished by Newton.
  double x3 = -c2 - x1_ - x2_;
  if (c0 > 0.0 && x1_ < 0.0 && x2_ > 0.0) {
    x3 = -c0 / (x1_ * x2_);
  } else if (x1_ < 0.0 && x2_ == 0.0) {
    x3 = c1 / x1_;
  } else if (x1_ == 0.0 && x2_ > 0.0) {
    x3 = c1 / x2_;
  }
  x3 = std::max(x3, one_minus_u0);
  for (int k = 0; k < 3; ++k) {
    const double value = c0 + x3 * (c1 + x3 * (c2 + x3));
    const double slope = c1 + x3 * (2.0 * c2 + 3.0 * x3);
    if (!(slope > 0.0)) break;
    const double next = x3 - value / slope;
    if (!(next >= one_minus_u0) || next == x3) break;
    x3 = next;
  }
  x3_ = x3;
  span_ = x2_ - x1_;
  // The distances to the poles: 1 + u1 = one_plus_u0 + x1 cancels when the top swings down
  // to near u = -1, but f(-1) = -(b + a)^2 = -beta (1 + u1)(1 + u2)(1 + u3) gives it to full
  // relative accuracy from b + a (exactly zero for a top through straight down); likewise
  // 1 - u2 from (b - a)^2 = beta (1 - u1)(1 - u2)(u3 - 1) while u3 - 1 is not itself small.
  one_plus_u1_ = one_plus_u0 + x1_;
  one_minus_u2_ = one_minus_u0 - x2_;
  const double one_plus_u2 = one_plus_u0 + x2_, one_plus_u3 = one_plus_u0 + x3;
  if (one_plus_u2 > 0.0) one_plus_u1_ = bpa_ * bpa_ / (beta_ * one_plus_u2 * one_plus_u3);
  const double one_minus_u1 = one_minus_u0 - x1_, u3_minus_1 = x3 - one_minus_u0;
  if (one_minus_u1 > 0.0 && u3_minus_1 > 1e-4 * std::max(1.0, x3)) {
    one_minus_u2_ = bma_ * bma_ / (beta_ * one_minus_u1 * u3_minus_1);
  }
  u1_ = one_plus_u1_ - 1.0;
  u2_ = std::max(1.0 - one_minus_u2_, u1_);
  through_bottom_ = !(one_plus_u1_ > 0.0);
  through_top_ = !(one_minus_u2_ > 0.0);
}

void LagrangeTop::set_nutation(double udot0) {
  if (!(span_ > 0.0)) {
    regime_ = Regime::kSteady;
    u1_ = u2_ = 0.5 * (u1_ + u2_);
    span_ = 0.0;
    return;
  }
  regime_ = Regime::kNutating;
  const double width = x3_ - x1_;
  lambda_ = 0.5 * std::sqrt(beta_ * width);
  parameter_ = elliptic_parameter(span_ / width, (x3_ - x2_) / width);
  // tau0 in [-K, K] from sn^2 = (u0 - u1) / (u2 - u1), cn^2 = (u2 - u0) / (u2 - u1), and
  // du/dt = 2 (u2 - u1) lambda sn cn dn: sn takes the sign of du/dt.
  double sn0 = std::sqrt(-x1_ / span_) * (udot0 < 0.0 ? -1.0 : 1.0);
  double cn0 = std::sqrt(x2_ / span_);
  const double r0 = std::hypot(sn0, cn0);
  sn0 /= r0;
  cn0 /= r0;
  tau0_ = sn0 * carlson_rf(cn0 * cn0, cn0 * cn0 + parameter_.m1 * sn0 * sn0, 1.0);
}

void LagrangeTop::set_precession() {
  if (regime_ != Regime::kNutating) return;
  const double one_minus_u1 = one_minus_u2_ + span_;
  if (!through_bottom_) {
    n_minus_ = -span_ / one_plus_u1_;
    c_minus_ = bpa_ / (one_plus_u1_ * lambda_);
  }
  if (!through_top_) {
    n_plus_ = span_ / one_minus_u1;
    c_plus_ = bma_ / (one_minus_u1 * lambda_);
  }
  const double k = parameter_.quarter;
  if (!std::isfinite(k)) return;  // u2 = u3: one asymptotic approach, no period
  // Pi(n|m) with 1 - n = (1 +- u2) / (1 +- u1).
  const auto complete = [&](double n, double one_minus_n) {
    return third_kind_complete(n, one_minus_n, parameter_);
  };
  const double linear = 2.0 * k * rate_ / lambda_;
  if (!through_bottom_) {
    const double one_plus_u2 = one_plus_u1_ + span_;
    sigma_half_ = 2.0 * c_minus_ * complete(n_minus_, one_plus_u2 / one_plus_u1_);
  }
  if (!through_top_) {
    delta_half_ = 2.0 * c_plus_ * complete(n_plus_, one_minus_u2_ / one_minus_u1);
  }
  sigma_half_ = std::remainder(linear + sigma_half_, 4.0 * kPi);
  delta_half_ = std::remainder(-linear + delta_half_, 4.0 * kPi);
}

LagrangeTop::Local LagrangeTop::local(double t) const {
  // Half angles of the tilt, their rates, and the two angle sums with their rates.
  double cos_half = 0.0, sin_half = 0.0, cos_rate = 0.0, sin_rate = 0.0;
  double sigma = 0.0, delta = 0.0, sigma_rate = rate_, delta_rate = -rate_;
  if (regime_ == Regime::kSteady) {
    cos_half = std::sqrt(0.5 * std::max(one_plus_u1_, 0.0));
    sin_half = std::sqrt(0.5 * std::max(one_minus_u2_, 0.0));
    if (!through_bottom_) sigma_rate += bpa_ / one_plus_u1_;
    if (!through_top_) delta_rate += bma_ / one_minus_u2_;
    sigma = std::remainder(sigma_rate * t, 4.0 * kPi);
    delta = std::remainder(delta_rate * t, 4.0 * kPi);
  } else {
    const double tau = tau0_ + lambda_ * t;
    const double k = parameter_.quarter;
    double j = 0.0, tr = tau;
    if (std::isfinite(k)) {
      j = std::nearbyint(tau / (2.0 * k));
      if (j != 0.0) tr = tau - j * (2.0 * k);
    }
    const JacobiElliptic e = jacobi_elliptic(tr, parameter_);
    const double sn = e.sn, cn = std::abs(e.cn), dn = e.dn;
    const double parity = std::fmod(j, 2.0) != 0.0 ? -1.0 : 1.0;
    const double root_span = std::sqrt(0.5 * span_);
    const double udot = 2.0 * span_ * lambda_ * sn * cn * dn;
    const double one_plus_u = one_plus_u1_ + span_ * sn * sn;
    const double one_minus_u = one_minus_u2_ + span_ * cn * cn;
    if (through_bottom_) {
      cos_half = root_span * parity * sn;
      cos_rate = root_span * parity * lambda_ * cn * dn;
    } else {
      cos_half = std::sqrt(0.5 * one_plus_u);
      cos_rate = udot / (4.0 * cos_half);
      sigma_rate += bpa_ / one_plus_u;
    }
    if (through_top_) {
      sin_half = root_span * parity * cn;
      sin_rate = -root_span * parity * lambda_ * sn * dn;
    } else {
      sin_half = std::sqrt(0.5 * one_minus_u);
      sin_rate = -udot / (4.0 * sin_half);
      delta_rate += bma_ / one_minus_u;
    }
    const double linear = rate_ * (tr - tau0_) / lambda_;
    sigma = linear;
    delta = -linear;
    if (!through_bottom_) {
      sigma += c_minus_ * third_kind(n_minus_, one_plus_u / one_plus_u1_, tr, e, parameter_.m);
    }
    if (!through_top_) {
      const double one_minus_u1 = one_minus_u2_ + span_;
      delta += c_plus_ * third_kind(n_plus_, one_minus_u / one_minus_u1, tr, e, parameter_.m);
    }
    if (j != 0.0) {
      sigma += std::remainder(j * sigma_half_, 4.0 * kPi);
      delta += std::remainder(j * delta_half_, 4.0 * kPi);
    }
  }
  const double cs = std::cos(0.5 * sigma), ss = std::sin(0.5 * sigma);
  const double cd = std::cos(0.5 * delta), sd = std::sin(0.5 * delta);
  const Eigen::Quaterniond q(cos_half * cs, sin_half * cd, sin_half * sd, cos_half * ss);
  const Eigen::Quaterniond dq(cos_rate * cs - 0.5 * cos_half * ss * sigma_rate,
                              sin_rate * cd - 0.5 * sin_half * sd * delta_rate,
                              sin_rate * sd + 0.5 * sin_half * cd * delta_rate,
                              cos_rate * ss + 0.5 * cos_half * cs * sigma_rate);
  // World-type angular velocity of the top frame in the vertical frame: w = 2 dq q*.
  const Eigen::Vector3d omega = 2.0 * (dq * q.conjugate()).vec();
  const Eigen::Vector3d axis = q * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d w_perp = omega - omega.dot(axis) * axis;
  return {q, l3_ * axis + i1_ * w_perp};
}

void LagrangeTop::anchor(const Eigen::Quaterniond& orientation0, const Eigen::Vector3d& axis0,
                         const Eigen::Vector3d& momentum0) {
  // The vertical frame: z along up, turned about z so that the solution's initial axis and L
  // land on the body's (the least-squares turn of their horizontal parts: the axis fixes it
  // when tilted, L when the axis starts vertical, where its azimuth means nothing). The body
  // offset then carries the principal frame onto the top frame (symmetry axis onto z), so
  // at(0) is the initial orientation.
  const Eigen::Vector3d up = -total_gravity(body_).normalized();
  const Eigen::Quaterniond tilt = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), up);
  const Local start = local(0.0);
  const double scale = std::max(momentum0.norm(), std::numeric_limits<double>::min());
  const Eigen::Vector3d targets[2] = {tilt.conjugate() * axis0,
                                      tilt.conjugate() * momentum0 / scale};
  const Eigen::Vector3d solved[2] = {start.rotation * Eigen::Vector3d::UnitZ(),
                                     start.momentum / scale};
  double sine = 0.0, cosine = 0.0;
  for (int k = 0; k < 2; ++k) {
    sine += solved[k].x() * targets[k].y() - solved[k].y() * targets[k].x();
    cosine += solved[k].x() * targets[k].x() + solved[k].y() * targets[k].y();
  }
  const double turn = std::atan2(sine, cosine);
  vertical_ = tilt * Eigen::Quaterniond(Eigen::AngleAxisd(turn, Eigen::Vector3d::UnitZ()));
  body_offset_ = (start.rotation.conjugate() * vertical_.conjugate() * orientation0).normalized();
}

BodyState LagrangeTop::at(double t) const {
  BodyState state = initial_;
  switch (regime_) {
    case Regime::kInvalid:
      state.orientation = Eigen::Quaterniond(kNaN, kNaN, kNaN, kNaN);
      state.angular_momentum = Eigen::Vector3d::Constant(kNaN);
      state.position = state.velocity = Eigen::Vector3d::Constant(kNaN);
      return state;
    case Regime::kTorqueFree:
      state.orientation = free_->at(t).orientation;
      break;
    default: {
      const Local l = local(t);
      state.orientation = (vertical_ * l.rotation * body_offset_).normalized();
      state.angular_momentum = vertical_ * l.momentum;
      break;
    }
  }
  update_pivot_kinematics(body_, state);
  return state;
}

double LagrangeTop::nutation_period() const {
  if (regime_ != Regime::kNutating) return kInf;
  return 2.0 * parameter_.quarter / lambda_;
}

}  // namespace tumble::engine
