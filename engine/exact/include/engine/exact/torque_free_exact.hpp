#pragma once
/// @file Exact torque-free motion of a rigid body: the reference every integrator is measured
/// against, and the free flow of the splitting integrators.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "engine/exact/elliptic.hpp"

namespace tumble::engine {

/// Exact torque-free motion of a rigid body, in closed form (Jacobi elliptic functions for the
/// angular velocity, an elliptic integral of the third kind for the precession angle).
/// The body frame is a principal frame: the inertia tensor is diag(moments).
class TorqueFreeMotion {
 public:
  /// How the body moves, from the initial angular velocity.
  enum class Regime {
    kAtRest,             ///< omega = 0
    kPermanentRotation,  ///< omega along a principal axis (or any axis of a sphere)
    kAboutLargestAxis,   ///< G^2 > 2 T I2: omega circles the axis of the largest moment
    kAboutSmallestAxis,  ///< G^2 < 2 T I2: omega circles the axis of the smallest moment
    kSeparatrix,         ///< G^2 = 2 T I2 exactly (to rounding): one heteroclinic excursion
    kInvalid,            ///< non-finite angular velocity or orientation: every state is NaN
  };

  /// A state of the body.
  struct State {
    Eigen::Quaterniond orientation;  ///< body-to-world unit quaternion
    Eigen::Vector3d omega_body;      ///< angular velocity in body (principal) axes, rad/s
  };

  /// moments: principal moments in any order, finite and positive (throws std::invalid_argument
  /// otherwise; the triangle inequality is not needed by the solution). orientation: body-to-world
  /// quaternion at t = 0 (normalised here). omega_body: angular velocity in the body frame at
  /// t = 0. Non-finite orientation or omega do not throw: they give the kInvalid regime, whose
  /// states are NaN, so a step loop can detect them without exceptions.
  TorqueFreeMotion(const Eigen::Vector3d& moments, const Eigen::Quaterniond& orientation,
                   const Eigen::Vector3d& omega_body);

  /// The state at time t (any real t: negative, or many periods ahead).
  State at(double t) const;

  /// Period of omega_body, 4 K(m) / lambda; +inf at rest, for permanent rotations and on the
  /// separatrix.
  double omega_period() const;
  /// Time between successive sign changes of the intermediate-axis component of omega,
  /// 2 K(m) / lambda (the flip interval of the Dzhanibekov effect); +inf where there is no such
  /// oscillation: at rest, permanent rotations, the separatrix and symmetric bodies.
  double flip_interval() const;
  /// Increase of the precession angle (about the angular momentum) over one omega period; NaN
  /// where omega_period() is infinite.
  double precession_per_period() const;

  Regime regime() const { return regime_; }
  /// Elliptic parameter m = k^2 of the motion (0 for symmetric bodies and trivial regimes).
  double parameter() const { return m_; }
  /// Kinetic energy T = omega . I omega / 2.
  double energy() const { return energy_; }
  /// Angular momentum in world axes (constant).
  const Eigen::Vector3d& angular_momentum_world() const { return angular_momentum_world_; }

 private:
  // Body-frame quantities at internal scaled time tau, before mapping to the caller's frame.
  struct Local {
    Eigen::Vector3d omega;     // internal frame, divided by scale_
    Eigen::Quaterniond euler;  // Rz(phi) Rx(theta) Rz(psi)
  };
  Local local(double tau) const;
  double pi_tilde(double u_reduced, double sn, double cn, double dn) const;

  // Construction steps, in order.
  struct InternalStart {
    Eigen::Vector3d omega;  // internal frame, scaled
    bool about_largest;     // omega circles the axis of the largest moment
  };
  /// Sorts and signs the axes (to_internal_, j_); the scaled omega in the internal frame.
  InternalStart enter_internal_frame(const Eigen::Vector3d& jn, const Eigen::Vector3d& w);
  /// Amplitudes, rate, parameter and regime; false for a permanent rotation (a or b zero).
  bool solve_elliptic(const InternalStart& start);
  /// Signs s1, s2 and the initial argument u0.
  void set_initial_argument(const Eigen::Vector3d& wi);
  /// K(m) and the precession per half period.
  void set_half_period();

  Regime regime_ = Regime::kAtRest;
  Eigen::Quaterniond orientation0_ = Eigen::Quaterniond::Identity();
  Eigen::Vector3d omega0_ = Eigen::Vector3d::Zero();
  double energy_ = 0.0;
  Eigen::Vector3d angular_momentum_world_ = Eigen::Vector3d::Zero();

  // Time scale (a power of two): internal time tau = scale_ * t, internal omega = omega / scale_.
  double scale_ = 0.0;
  // Internal frame: omega_internal = to_internal_ * omega_body; moments j_ scaled to ~1.
  Eigen::Matrix3d to_internal_ = Eigen::Matrix3d::Identity();
  Eigen::Quaterniond to_internal_q_ = Eigen::Quaterniond::Identity();
  Eigen::Quaterniond prefix_ = Eigen::Quaterniond::Identity();
  Eigen::Vector3d j_ = Eigen::Vector3d::Ones();
  // Elliptic solution: omega = (s1 A1 cn, s2 A2 sn, A3 dn)(u), u = u0 + lambda tau.
  Eigen::Vector3d amplitude_ = Eigen::Vector3d::Zero();
  double s1_ = 1.0;
  double s2_ = 1.0;
  double lambda_ = 0.0;
  double m_ = 0.0;
  double m1_ = 1.0;
  EllipticParameter parameter_;
  double k_ = 0.0;  // K(m), +inf on the separatrix
  double n_ = 0.0;  // characteristic of the third-kind integral (<= 0)
  double g_ = 0.0;  // |L| (internal units)
  double c_ = 0.0;  // G (J3 - J1) / (J1 J3)
  double u0_ = 0.0;
  double phi_half_ = 0.0;      // precession over one half period (2K in u)
  double phi_half_mod_ = 0.0;  // the same reduced to (-2 pi, 2 pi]
};

}  // namespace tumble::engine
