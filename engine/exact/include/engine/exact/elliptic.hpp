#pragma once
/// @file Jacobi elliptic functions and elliptic integrals in double precision.
///
/// Conventions (Abramowitz & Stegun ch. 16-17): the parameter is m = k^2 in [0, 1]; functions
/// that are sensitive near m = 1 also take the complementary parameter m1 = 1 - m, which the
/// caller should compute without cancellation when it is small (the torque-free solution does).
///   F(phi|m)      = int_0^phi dt / sqrt(1 - m sin^2 t)
///   Pi(n; phi|m)  = int_0^phi dt / ((1 - n sin^2 t) sqrt(1 - m sin^2 t))   (n < 1)
///   K(m) = F(pi/2|m),  Pi(n|m) = Pi(n; pi/2|m)
/// The integrals are evaluated through Carlson's symmetric forms R_F, R_J, R_C (B. C. Carlson,
/// "Numerical computation of real or complex elliptic integrals", Numer. Algorithms 10, 1995;
/// DLMF 19.36(i)).

namespace tumble::engine {

/// sn(u|m), cn(u|m), dn(u|m), evaluated together.
struct JacobiElliptic {
  double sn = 0.0;
  double cn = 1.0;
  double dn = 1.0;
};

/// A parameter m with its complement and both quarter periods, for repeated evaluations.
struct EllipticParameter {
  double m = 0.0;              ///< m = k^2
  double m1 = 1.0;             ///< 1 - m
  double quarter = 0.0;        ///< K(m), +inf at m = 1
  double quarter_prime = 0.0;  ///< K'(m) = K(1 - m), +inf at m = 0
};
/// Builds an EllipticParameter from m and an accurately known m1 = 1 - m.
EllipticParameter elliptic_parameter(double m, double m1);

/// Jacobi elliptic functions for m in [0, 1]. sn from the amplitude by the descending
/// Landen / AGM method (A&S 16.4). Near m = 1 (m1 < 1e-4) and |u| <= K, cn and dn come from
/// their sums over images (Jacobi's imaginary transformation of the Fourier series),
///   dn(u) = pi/(2K') sum_n sech(pi (u - 2nK)/(2K')),
///   cn(u) = pi/(2kK') sum_n (-1)^n sech(pi (u - 2nK)/(2K')),
/// which keeps their relative accuracy where they are small (cos(am) only has absolute
/// accuracy there). Exact limits at m = 0 (sin, cos, 1) and m1 = 0 (tanh, sech, sech).
/// Reduce |u| to a few K before calling.
JacobiElliptic jacobi_elliptic(double u, const EllipticParameter& parameter);
/// Same, for m in [0, 1] and m1 = 1 - m given accurately.
JacobiElliptic jacobi_elliptic(double u, double m, double m1);
/// Same with m1 = 1 - m.
JacobiElliptic jacobi_elliptic(double u, double m);

/// Jacobi amplitude am(u|m): the angle with sin(am) = sn, cos(am) = cn, continuous in u.
double jacobi_amplitude(double u, double m, double m1);

/// Carlson's R_F(x, y, z) = 1/2 int_0^inf dt / sqrt((t+x)(t+y)(t+z)); x, y, z >= 0, at most one
/// of them zero.
double carlson_rf(double x, double y, double z);
/// Carlson's R_J(x, y, z, p) = 3/2 int_0^inf dt / ((t+p) sqrt((t+x)(t+y)(t+z))); x, y, z >= 0
/// with at most one zero, p > 0.
double carlson_rj(double x, double y, double z, double p);
/// Carlson's R_C(x, y) = 1/2 int_0^inf dt / ((t+y) sqrt(t+x)); x >= 0, y > 0.
double carlson_rc(double x, double y);

/// Complete elliptic integral of the first kind K(m) from the complementary parameter
/// m1 = 1 - m (arithmetic-geometric mean, A&S 17.6); +inf at m1 = 0.
double elliptic_k_complement(double m1);
/// K(m) for m in [0, 1].
double elliptic_k(double m);
/// Incomplete integral of the first kind F(phi|m) for any real phi (quasi-periodic extension
/// F(phi + j pi) = F(phi) + 2 j K).
double elliptic_f(double phi, double m, double m1);
double elliptic_f(double phi, double m);
/// Complete integral of the third kind Pi(n|m), n < 1.
double elliptic_pi_complete(double n, double m, double m1);
double elliptic_pi_complete(double n, double m);
/// Incomplete integral of the third kind Pi(n; phi|m), n < 1, any real phi.
double elliptic_pi(double n, double phi, double m, double m1);
double elliptic_pi(double n, double phi, double m);

}  // namespace tumble::engine
