#pragma once
/// @file Exact motion of the heavy symmetric (Lagrange) top: the reference for pivoted
/// symmetric bodies under gravity, and the `exact` integrator's solution for them
/// (engine/PHYSICS.md §4b).

#include <optional>
#include <string>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "engine/body/rigid_body.hpp"
#include "engine/exact/elliptic.hpp"
#include "engine/exact/torque_free_exact.hpp"

namespace tumble::engine {

/// Relative tolerance to which a Lagrange top's two transverse moments must agree, and its
/// centre of mass lie on the symmetry axis (off-axis components against the offset's length).
/// The solution uses the mean of the two moments, so a residual asymmetry of this size moves
/// the orientation by about this much per radian of spin.
inline constexpr double kLagrangeTopTolerance = 1e-12;

/// Why `body` is not a Lagrange top, or nothing when it is one: pivoted, only uniform gravity
/// among its force terms, and either no gravity torque at all (no gravity, or the centre of
/// mass at the pivot: then it is a free rotor about the pivot, of any shape) or two equal
/// principal moments (to kLagrangeTopTolerance) with the centre of mass on the third axis.
std::optional<std::string> lagrange_top_problem(const BodyModel& body);
/// True when lagrange_top_problem finds nothing.
bool is_lagrange_top(const BodyModel& body);

/// The closed-form motion of a Lagrange top from its initial state (Goldstein, Classical
/// Mechanics §5.7; Landau and Lifshitz, Mechanics §35): u = cos(tilt) between the two roots
/// u1 <= u2 of a cubic, u = u1 + (u2 - u1) sn^2(lambda t + tau0 | m), the spin about the axis
/// constant, the precession and spin angles from elliptic integrals of the third kind.
class LagrangeTop {
 public:
  /// How the top moves.
  enum class Regime {
    kTorqueFree,  ///< no gravity torque (no gravity, or centre of mass at the pivot)
    kSteady,      ///< u1 = u2: steady precession, sleeping, hanging, at rest
    kNutating,    ///< u oscillates between u1 < u2
    kInvalid,     ///< non-finite initial state: every state is NaN
  };

  /// Throws InputError when `body` is not a Lagrange top (the message of
  /// lagrange_top_problem). `initial` is the body's state at t = 0.
  LagrangeTop(const BodyModel& body, const BodyState& initial);

  /// The state at time t >= 0: orientation and world L from the solution, centre of mass from
  /// the pivot kinematics.
  BodyState at(double t) const;

  Regime regime() const { return regime_; }
  /// Lower and upper turning points of u = cos(tilt from the vertical); both the initial u when
  /// the regime is not kNutating.
  double u_min() const { return u1_; }
  double u_max() const { return u2_; }
  /// Period of the nutation (of u), 2 K(m) / lambda; +inf unless kNutating.
  double nutation_period() const;
  /// Elliptic parameter m = (u2 - u1) / (u3 - u1) of the nutation.
  double parameter() const { return parameter_.m; }

 private:
  // The solution in the vertical frame (z up) before the two fixed rotations.
  struct Local {
    Eigen::Quaterniond rotation;  // top frame (z along the axis) to the vertical frame
    Eigen::Vector3d momentum;     // L in the vertical frame
  };
  Local local(double t) const;
  void solve_roots(double one_minus_u0, double one_plus_u0, double udot0, double k0, double p0);
  void set_nutation(double udot0);
  void set_precession();
  void anchor(const Eigen::Quaterniond& orientation0, const Eigen::Vector3d& axis0,
              const Eigen::Vector3d& momentum0);

  BodyModel body_;
  BodyState initial_;
  Regime regime_ = Regime::kSteady;
  std::optional<TorqueFreeMotion> free_;  // kTorqueFree only

  double i1_ = 1.0;    // transverse moment (mean of the equal pair)
  double l3_ = 0.0;    // L . axis
  double beta_ = 0.0;  // 2 m g l / I1
  // Roots as offsets from u0 (x = u - u0) and the distances the solution needs.
  double x1_ = 0.0, x2_ = 0.0, x3_ = 0.0;
  double u1_ = 0.0, u2_ = 0.0;
  double span_ = 0.0;            // u2 - u1
  double one_plus_u1_ = 0.0;     // 1 + u1
  double one_minus_u2_ = 0.0;    // 1 - u2
  bool through_bottom_ = false;  // u1 = -1: the axis passes through straight down
  bool through_top_ = false;     // u2 = 1: the axis passes through the vertical
  // Nutation: tau = tau0 + lambda t.
  double lambda_ = 0.0;
  double tau0_ = 0.0;
  EllipticParameter parameter_;
  // Sigma = phi + psi and Delta = phi - psi: d/dt = +-rate_ + (b +- a) / (1 +- u), the pole
  // terms written as lambda c_ / (1 - n_ sn^2) in tau; bpa_, bma_ = b +- a = L . (up +- axis) / I1.
  double rate_ = 0.0;                                 // L3 / I3 - L3 / I1
  double n_minus_ = 0.0, c_minus_ = 0.0, bpa_ = 0.0;  // Sigma: 1 + u
  double n_plus_ = 0.0, c_plus_ = 0.0, bma_ = 0.0;    // Delta: 1 - u
  double sigma_half_ = 0.0, delta_half_ = 0.0;        // gained per half period, mod 4 pi
  // Fixed rotations: world = vertical_ * local * body_offset_.
  Eigen::Quaterniond vertical_ = Eigen::Quaterniond::Identity();
  Eigen::Quaterniond body_offset_ = Eigen::Quaterniond::Identity();
};

}  // namespace tumble::engine
