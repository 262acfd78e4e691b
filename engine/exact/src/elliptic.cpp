// Jacobi elliptic functions and elliptic integrals.
//
// Design: everything rests on two primitives that are accurate over the whole range m in [0, 1].
//  - The amplitude am(u|m) by the descending Landen transformation / arithmetic-geometric mean
//    (A&S 16.4): a_0 = 1, b_0 = sqrt(m1), c_0 = sqrt(m), phi_N = 2^N a_N u, then
//    phi_{i-1} = (phi_i + asin(c_i sin(phi_i) / a_i)) / 2. sn and cn are sin and cos of the
//    amplitude, and dn = sqrt(cn^2 + m1 sn^2), a sum of two positive terms (no cancellation
//    near m = 1, unlike 1 - m sn^2).
//  - Carlson's symmetric integrals R_F, R_J by the duplication theorem with the fifth/seventh
//    order Taylor tails of Carlson (1995), Numer. Algorithms 10, and DLMF 19.36.1-2.
// Legendre's forms follow from DLMF 19.25.5 and 19.25.14:
//   F(phi|m)     = s R_F(c^2, c^2 + m1 s^2, 1)
//   Pi(n;phi|m)  = F(phi|m) + (n/3) s^3 R_J(c^2, c^2 + m1 s^2, 1, 1 - n s^2),  s = sin, c = cos.
#include "engine/exact/elliptic.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace tumble::engine {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr int kMaxDuplications = 80;  // 4^-80 ~ 1e-48: far beyond any needed reduction
constexpr int kMaxAgm = 40;
// Below this complementary parameter cn and dn are summed over images (relative accuracy).
constexpr double kNearOne = 1e-4;

// R_C(1, 1 + e) = atan(sqrt(e)) / sqrt(e) (e > 0), atanh(sqrt(-e)) / sqrt(-e) (-1 < e < 0);
// the series sum_k (-e)^k / (2k + 1) for small |e| (the common case inside R_J).
double rc_one_plus(double e) {
  if (std::abs(e) < 1e-3) {
    return 1.0 + e * (-1.0 / 3.0 +
                      e * (1.0 / 5.0 +
                           e * (-1.0 / 7.0 + e * (1.0 / 9.0 + e * (-1.0 / 11.0 + e / 13.0)))));
  }
  if (e > 0.0) {
    const double s = std::sqrt(e);
    return std::atan(s) / s;
  }
  const double s = std::sqrt(-e);
  return std::atanh(s) / s;
}

// The Landen/AGM sequence for parameter (m, m1): a_i and c_i, i = 0..n.
struct AgmSequence {
  std::array<double, kMaxAgm + 1> a{};
  std::array<double, kMaxAgm + 1> c{};
  int n = 0;
};

AgmSequence agm_sequence(double m, double m1) {
  AgmSequence s;
  s.a[0] = 1.0;
  s.c[0] = std::sqrt(m);
  double b = std::sqrt(m1);
  int i = 0;
  while (i < kMaxAgm && s.c[i] > 0.5 * kEps * s.a[i]) {
    const double a_next = 0.5 * (s.a[i] + b);
    // c_{i+1} = (a_i - b_i)/2 = c_i^2 / (4 a_{i+1}), without the cancellation of the difference.
    s.c[i + 1] = s.c[i] * s.c[i] / (4.0 * a_next);
    b = std::sqrt(s.a[i] * b);
    s.a[i + 1] = a_next;
    ++i;
  }
  s.n = i;
  return s;
}

// Reduces phi to phi - j pi with the remainder in [-pi/2, pi/2]; returns j.
double reduce_by_pi(double phi, double& reduced) {
  const double j = std::nearbyint(phi / std::numbers::pi);
  reduced = phi - j * std::numbers::pi;
  return j;
}

}  // namespace

double jacobi_amplitude(double u, double m, double m1) {
  if (m1 <= 0.0) return 2.0 * std::atan(std::tanh(0.5 * u));  // Gudermannian, A&S 16.15
  if (m <= 0.0) return u;
  const AgmSequence s = agm_sequence(m, m1);
  double phi = std::ldexp(s.a[s.n] * u, s.n);
  for (int i = s.n; i > 0; --i) phi = 0.5 * (phi + std::asin(s.c[i] / s.a[i] * std::sin(phi)));
  return phi;
}

EllipticParameter elliptic_parameter(double m, double m1) {
  EllipticParameter p;
  p.m = m;
  p.m1 = m1;
  p.quarter = elliptic_k_complement(m1);
  p.quarter_prime = elliptic_k_complement(m);
  return p;
}

JacobiElliptic jacobi_elliptic(double u, const EllipticParameter& parameter) {
  const double m = parameter.m;
  const double m1 = parameter.m1;
  JacobiElliptic r;
  if (m1 <= 0.0) {
    // m = 1: sn = tanh, cn = dn = sech (A&S 16.6.1-3).
    r.sn = std::tanh(u);
    r.cn = 1.0 / std::cosh(u);
    r.dn = r.cn;
    return r;
  }
  const double phi = jacobi_amplitude(u, m, m1);
  r.sn = std::sin(phi);
  r.cn = std::cos(phi);
  if (m <= 0.0) {
    r.dn = 1.0;
  } else if (m1 < kNearOne && std::abs(u) <= parameter.quarter) {
    // Sums over images: terms decay like sech((|n| - 1/2) pi K / K'), i.e. fast when m1 is small.
    const double scale = std::numbers::pi / (2.0 * parameter.quarter_prime);
    const double x = scale * u;
    const double step = 2.0 * scale * parameter.quarter;
    double dn_sum = 1.0 / std::cosh(x);
    double cn_sum = dn_sum;
    double sign = -1.0;
    for (int n = 1; n < 64; ++n) {
      const double terms = 1.0 / std::cosh(x - n * step) + 1.0 / std::cosh(x + n * step);
      dn_sum += terms;
      cn_sum += sign * terms;
      sign = -sign;
      if (terms <= 1e-18 * dn_sum) break;
    }
    r.dn = scale * dn_sum;
    r.cn = scale * cn_sum / std::sqrt(m);
  } else {
    r.dn = std::sqrt(r.cn * r.cn + m1 * r.sn * r.sn);
  }
  return r;
}

JacobiElliptic jacobi_elliptic(double u, double m, double m1) {
  if (m1 <= 0.0 || m <= 0.0 || m1 >= kNearOne) {
    EllipticParameter p;
    p.m = m;
    p.m1 = m1;
    return jacobi_elliptic(u, p);
  }
  return jacobi_elliptic(u, elliptic_parameter(m, m1));
}

JacobiElliptic jacobi_elliptic(double u, double m) {
  return jacobi_elliptic(u, m, 1.0 - m);
}

double carlson_rc(double x, double y) {
  // Duplication (Carlson 1995, algorithm for R_C), y > 0.
  const double a0 = (x + 2.0 * y) / 3.0;
  const double q = std::pow(3.0 * kEps, -1.0 / 8.0) * std::abs(a0 - x);
  double a = a0;
  double fmn = 1.0;
  for (int i = 0; i < kMaxDuplications && fmn * q > std::abs(a); ++i) {
    const double lambda = 2.0 * std::sqrt(x) * std::sqrt(y) + y;
    a = 0.25 * (a + lambda);
    x = 0.25 * (x + lambda);
    y = 0.25 * (y + lambda);
    fmn *= 0.25;
  }
  // s = (y_0 - A_0) / (4^n A_n), written with the current iterates: y_n - A_n = 4^-n (y_0 - A_0).
  const double t = (y - a) / a;
  return (1.0 + t * t *
                    (3.0 / 10.0 +
                     t * (1.0 / 7.0 + t * (3.0 / 8.0 + t * (9.0 / 22.0 + t * (159.0 / 208.0 +
                                                                              t * 9.0 / 8.0)))))) /
         std::sqrt(a);
}

double carlson_rf(double x, double y, double z) {
  const double a0 = (x + y + z) / 3.0;
  const double q = std::pow(3.0 * kEps, -1.0 / 6.0) *
                   std::max({std::abs(a0 - x), std::abs(a0 - y), std::abs(a0 - z)});
  const double x0 = x;
  const double y0 = y;
  double a = a0;
  double fmn = 1.0;
  for (int i = 0; i < kMaxDuplications && fmn * q >= std::abs(a); ++i) {
    const double sx = std::sqrt(x);
    const double sy = std::sqrt(y);
    const double sz = std::sqrt(z);
    const double lambda = sx * sy + sx * sz + sy * sz;
    a = 0.25 * (a + lambda);
    x = 0.25 * (x + lambda);
    y = 0.25 * (y + lambda);
    z = 0.25 * (z + lambda);
    fmn *= 0.25;
  }
  const double xx = fmn * (a0 - x0) / a;
  const double yy = fmn * (a0 - y0) / a;
  const double zz = -(xx + yy);
  const double e2 = xx * yy - zz * zz;
  const double e3 = xx * yy * zz;
  return (1.0 - e2 / 10.0 + e3 / 14.0 + e2 * e2 / 24.0 - 3.0 * e2 * e3 / 44.0) / std::sqrt(a);
}

double carlson_rj(double x, double y, double z, double p) {
  const double a0 = (x + y + z + 2.0 * p) / 5.0;
  const double delta = (p - x) * (p - y) * (p - z);
  const double q =
      std::pow(0.25 * kEps, -1.0 / 6.0) *
      std::max({std::abs(a0 - x), std::abs(a0 - y), std::abs(a0 - z), std::abs(a0 - p)});
  const double x0 = x;
  const double y0 = y;
  const double z0 = z;
  double a = a0;
  double fmn = 1.0;
  double sum = 0.0;
  for (int i = 0; i < kMaxDuplications && fmn * q >= std::abs(a); ++i) {
    const double sx = std::sqrt(x);
    const double sy = std::sqrt(y);
    const double sz = std::sqrt(z);
    const double sp = std::sqrt(p);
    const double lambda = sx * sy + sx * sz + sy * sz;
    const double d = (sp + sx) * (sp + sy) * (sp + sz);
    const double e = fmn * fmn * fmn * delta / (d * d);
    sum += fmn * rc_one_plus(e) / d;
    a = 0.25 * (a + lambda);
    x = 0.25 * (x + lambda);
    y = 0.25 * (y + lambda);
    z = 0.25 * (z + lambda);
    p = 0.25 * (p + lambda);
    fmn *= 0.25;
  }
  const double xx = fmn * (a0 - x0) / a;
  const double yy = fmn * (a0 - y0) / a;
  const double zz = fmn * (a0 - z0) / a;
  const double pp = -0.5 * (xx + yy + zz);
  const double xyz = xx * yy * zz;
  const double e2 = xx * yy + xx * zz + yy * zz - 3.0 * pp * pp;
  const double e3 = xyz + 2.0 * e2 * pp + 4.0 * pp * pp * pp;
  const double e4 = (2.0 * xyz + e2 * pp + 3.0 * pp * pp * pp) * pp;
  const double e5 = xyz * pp * pp;
  const double tail = 1.0 - 3.0 * e2 / 14.0 + e3 / 6.0 + 9.0 * e2 * e2 / 88.0 - 3.0 * e4 / 22.0 -
                      9.0 * e2 * e3 / 52.0 + 3.0 * e5 / 26.0;
  return fmn * tail / (a * std::sqrt(a)) + 6.0 * sum;
}

double elliptic_k_complement(double m1) {
  if (m1 <= 0.0) return std::numeric_limits<double>::infinity();
  // K = pi / (2 AGM(1, sqrt(m1))) (A&S 17.6).
  double a = 1.0;
  double b = std::sqrt(m1);
  for (int i = 0; i < kMaxAgm && std::abs(a - b) > kEps * a; ++i) {
    const double a_next = 0.5 * (a + b);
    b = std::sqrt(a * b);
    a = a_next;
  }
  return std::numbers::pi / (a + b);
}

double elliptic_k(double m) {
  return elliptic_k_complement(1.0 - m);
}

double elliptic_f(double phi, [[maybe_unused]] double m, double m1) {
  double reduced = 0.0;
  const double j = reduce_by_pi(phi, reduced);
  const double s = std::sin(reduced);
  const double c = std::cos(reduced);
  const double c2 = c * c;
  const double f = s * carlson_rf(c2, c2 + m1 * s * s, 1.0);
  return j == 0.0 ? f : 2.0 * j * elliptic_k_complement(m1) + f;
}

double elliptic_f(double phi, double m) {
  return elliptic_f(phi, m, 1.0 - m);
}

double elliptic_pi_complete(double n, [[maybe_unused]] double m, double m1) {
  if (m1 <= 0.0) return std::numeric_limits<double>::infinity();
  return elliptic_k_complement(m1) + n / 3.0 * carlson_rj(0.0, m1, 1.0, 1.0 - n);
}

double elliptic_pi_complete(double n, double m) {
  return elliptic_pi_complete(n, m, 1.0 - m);
}

double elliptic_pi(double n, double phi, double m, double m1) {
  double reduced = 0.0;
  const double j = reduce_by_pi(phi, reduced);
  const double s = std::sin(reduced);
  const double c = std::cos(reduced);
  const double c2 = c * c;
  const double d2 = c2 + m1 * s * s;
  const double s2 = s * s;
  const double p =
      s * carlson_rf(c2, d2, 1.0) + n / 3.0 * s * s2 * carlson_rj(c2, d2, 1.0, 1.0 - n * s2);
  return j == 0.0 ? p : 2.0 * j * elliptic_pi_complete(n, m, m1) + p;
}

double elliptic_pi(double n, double phi, double m) {
  return elliptic_pi(n, phi, m, 1.0 - m);
}

}  // namespace tumble::engine
