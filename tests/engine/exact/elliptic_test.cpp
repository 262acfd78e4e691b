// Jacobi elliptic functions and elliptic integrals against identities, limits, quadrature,
// libstdc++'s special functions and reference values (Carlson 1995 Table; A&S ch. 17; values
// checked with mpmath at 30 digits).
#include "engine/exact/elliptic.hpp"

#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

namespace tumble::engine {
namespace {

// Composite 3-point Gauss-Legendre quadrature in long double (exact for quintics per panel).
template <class F>
long double gauss3(F f, long double a, long double b, int panels) {
  const long double r = std::sqrt(0.6L);
  const long double h = (b - a) / panels;
  long double sum = 0.0L;
  for (int i = 0; i < panels; ++i) {
    const long double c = a + (i + 0.5L) * h;
    const long double hh = 0.5L * h;
    sum += hh * (5.0L / 9.0L * f(c - r * hh) + 8.0L / 9.0L * f(c) + 5.0L / 9.0L * f(c + r * hh));
  }
  return sum;
}

const std::vector<double> kParameters = {0.0, 1e-10, 0.1, 0.5, 0.8, 0.99, 1.0 - 1e-6, 1.0 - 1e-12};

TEST(Elliptic, CarlsonReferenceValues) {
  EXPECT_NEAR(carlson_rf(1.0, 2.0, 0.0), 1.31102877714605990523, 2e-16 * 1.3);
  EXPECT_NEAR(carlson_rf(2.0, 3.0, 4.0), 0.584082841677151706693, 2e-16);
  EXPECT_NEAR(carlson_rj(0.0, 1.0, 2.0, 3.0), 0.776886237785823320142, 4e-16);
  EXPECT_NEAR(carlson_rj(2.0, 3.0, 4.0, 5.0), 0.142975796671567538332, 1e-16);
  EXPECT_NEAR(carlson_rj(1e-12, 2e-12, 1.0, 4.0), 10.2868736580015192610, 1e-14);
  EXPECT_NEAR(carlson_rc(0.0, 0.25), std::numbers::pi, 4e-16);
  EXPECT_NEAR(carlson_rc(1.0, 2.0), std::atan(1.0), 2e-16);
  EXPECT_NEAR(carlson_rc(2.0, 1.0), std::acosh(std::sqrt(2.0)), 1e-15);
}

TEST(Elliptic, CompleteFirstKind) {
  EXPECT_DOUBLE_EQ(elliptic_k(0.0), std::numbers::pi / 2.0);
  // K(1/2) = Gamma(1/4)^2 / (4 sqrt(pi)).
  const double gamma = std::tgamma(0.25);
  EXPECT_NEAR(elliptic_k(0.5), gamma * gamma / (4.0 * std::sqrt(std::numbers::pi)), 1e-15);
  EXPECT_NEAR(elliptic_k(0.5), 1.85407467730137191843, 1e-15);
  EXPECT_NEAR(elliptic_k(0.9), 2.57809211334817329268, 1e-15);
  EXPECT_NEAR(elliptic_k_complement(1e-12), 15.2018049190877151742, 1e-14);
  EXPECT_TRUE(std::isinf(elliptic_k_complement(0.0)));
  for (double m : {0.05, 0.3, 0.7, 0.95}) {
    EXPECT_NEAR(elliptic_k(m), std::comp_ellint_1(std::sqrt(m)), 1e-15 * elliptic_k(m)) << m;
  }
}

TEST(Elliptic, IncompleteIntegralsAgainstQuadratureAndLibstdcxx) {
  for (double m : {0.0, 0.3, 0.9, 0.99}) {
    for (double phi : {0.2, 1.0, std::numbers::pi / 2.0, 2.5, -4.0}) {
      const long double f_quad = gauss3(
          [&](long double t) {
            const long double s = std::sin(t);
            return 1.0L / std::sqrt(1.0L - m * s * s);
          },
          0.0L, phi, 4000);
      EXPECT_NEAR(elliptic_f(phi, m), static_cast<double>(f_quad), 2e-15 * std::abs(phi));
      EXPECT_NEAR(elliptic_f(phi, m), std::ellint_1(std::sqrt(m), phi), 4e-15 * std::abs(phi));
      for (double n : {-20.0, -1.0, 0.0, 0.5, 0.9}) {
        const long double pi_quad = gauss3(
            [&](long double t) {
              const long double s = std::sin(t);
              return 1.0L / ((1.0L - n * s * s) * std::sqrt(1.0L - m * s * s));
            },
            0.0L, phi, 4000);
        const double expected = static_cast<double>(pi_quad);
        EXPECT_NEAR(elliptic_pi(n, phi, m), expected, 5e-15 * std::abs(expected))
            << "m=" << m << " n=" << n << " phi=" << phi;
        // libstdc++ uses the same sign convention, 1 - n sin^2 (the C++17 standard's).
        EXPECT_NEAR(std::ellint_3(std::sqrt(m), n, phi), expected, 1e-14 * std::abs(expected));
      }
    }
  }
  EXPECT_NEAR(elliptic_pi(-2.5, 1.2, 0.8), 0.848727497971917209390, 4e-16);
  EXPECT_NEAR(elliptic_pi_complete(0.6, 0.8), 3.90383109679683424531, 2e-15);
}

TEST(Elliptic, PythagoreanIdentities) {
  for (double m : kParameters) {
    const EllipticParameter p = elliptic_parameter(m, 1.0 - m);
    for (double u = -p.quarter; u <= p.quarter; u += p.quarter / 37.0) {
      const JacobiElliptic e = jacobi_elliptic(u, m);
      EXPECT_NEAR(e.sn * e.sn + e.cn * e.cn, 1.0, 1e-15) << m << " " << u;
      EXPECT_NEAR(e.dn * e.dn + m * e.sn * e.sn, 1.0, 1e-15) << m << " " << u;
      EXPECT_GE(e.cn, 0.0);
    }
  }
}

TEST(Elliptic, DerivativesByFiniteDifferences) {
  const double h = 1e-3;
  auto d5 = [&](auto f, double u) {
    return (-f(u + 2 * h) + 8.0 * f(u + h) - 8.0 * f(u - h) + f(u - 2 * h)) / (12.0 * h);
  };
  for (double m : {0.0, 0.3, 0.8, 0.999}) {
    for (double u : {-1.3, 0.1, 0.7, 1.5}) {
      const JacobiElliptic e = jacobi_elliptic(u, m);
      EXPECT_NEAR(d5([&](double x) { return jacobi_elliptic(x, m).sn; }, u), e.cn * e.dn, 1e-11);
      EXPECT_NEAR(d5([&](double x) { return jacobi_elliptic(x, m).cn; }, u), -e.sn * e.dn, 1e-11);
      EXPECT_NEAR(d5([&](double x) { return jacobi_elliptic(x, m).dn; }, u), -m * e.sn * e.cn,
                  1e-11);
    }
  }
}

TEST(Elliptic, Limits) {
  for (double u : {-2.0, -0.3, 0.0, 0.9, 3.0}) {
    const JacobiElliptic zero = jacobi_elliptic(u, 0.0);
    EXPECT_NEAR(zero.sn, std::sin(u), 2e-16);
    EXPECT_NEAR(zero.cn, std::cos(u), 2e-16);
    EXPECT_EQ(zero.dn, 1.0);
    const JacobiElliptic one = jacobi_elliptic(u, 1.0, 0.0);
    EXPECT_DOUBLE_EQ(one.sn, std::tanh(u));
    EXPECT_DOUBLE_EQ(one.cn, 1.0 / std::cosh(u));
    EXPECT_DOUBLE_EQ(one.dn, 1.0 / std::cosh(u));
    // Close to m = 1 the functions approach tanh/sech by O(m1) (A&S 16.15).
    const JacobiElliptic near = jacobi_elliptic(u, 1.0 - 1e-14, 1e-14);
    EXPECT_NEAR(near.sn, std::tanh(u), 1e-12);
    EXPECT_NEAR(near.cn, 1.0 / std::cosh(u), 1e-12);
  }
  EXPECT_DOUBLE_EQ(jacobi_amplitude(0.7, 0.0, 1.0), 0.7);
  EXPECT_NEAR(jacobi_amplitude(0.7, 1.0, 0.0), 2.0 * std::atan(std::tanh(0.35)), 1e-16);
}

TEST(Elliptic, InverseOfTheFirstKindIntegral) {
  for (double m : {0.2, 0.9, 1.0 - 1e-9}) {
    for (double phi : {0.1, 0.8, 1.5, 2.4}) {
      const JacobiElliptic e = jacobi_elliptic(elliptic_f(phi, m), m);
      EXPECT_NEAR(e.sn, std::sin(phi), 1e-14);
      EXPECT_NEAR(e.cn, std::cos(phi), 1e-14);
    }
  }
}

TEST(Elliptic, RelativeAccuracyNearParameterOne) {
  // mpmath at 30 digits: m1 = 1e-12, u = 9.
  const JacobiElliptic e = jacobi_elliptic(9.0, 1.0 - 1e-12, 1e-12);
  EXPECT_NEAR(e.sn, 0.999999969540290973822, 2e-16);
  EXPECT_NEAR(e.cn / 0.000246818591529412200596, 1.0, 1e-14);
  EXPECT_NEAR(e.dn / 0.000246820617300301533545, 1.0, 1e-14);
  // dn(u) dn(K - u) = sqrt(m1) (A&S 16.8.2 with u -> K - u) holds to relative rounding.
  for (double m1 : {1e-5, 1e-9, 1e-14}) {
    const EllipticParameter p = elliptic_parameter(1.0 - m1, m1);
    for (double u = 0.5; u < p.quarter - 0.5; u += 0.75) {
      const double product = jacobi_elliptic(u, p).dn * jacobi_elliptic(p.quarter - u, p).dn;
      EXPECT_NEAR(product / std::sqrt(m1), 1.0, 1e-13) << m1 << " " << u;
    }
  }
}

TEST(Elliptic, ThirdKindMatchesIntegralOverTheArgument) {
  // Pi(n; am u | m) = int_0^u du' / (1 - n sn^2 u'), the form the torque-free solution uses,
  // near m = 1 where the amplitude hides the argument.
  const double n = -3.0;
  for (double m1 : {1e-2, 1e-8, 1e-12}) {
    const EllipticParameter p = elliptic_parameter(1.0 - m1, m1);
    for (double fraction : {0.3, 0.9, 0.999}) {
      const double u = fraction * p.quarter;
      const long double quad = gauss3(
          [&](long double x) {
            const long double sn = jacobi_elliptic(static_cast<double>(x), p).sn;
            return 1.0L / (1.0L - n * sn * sn);
          },
          0.0L, u, 20000);
      const JacobiElliptic e = jacobi_elliptic(u, p);
      const double s2 = e.sn * e.sn;
      const double value =
          u + n / 3.0 * e.sn * s2 * carlson_rj(e.cn * e.cn, e.dn * e.dn, 1.0, 1.0 - n * s2);
      EXPECT_NEAR(value, static_cast<double>(quad), 1e-14 * u) << m1 << " " << fraction;
    }
  }
}

}  // namespace
}  // namespace tumble::engine
