#pragma once
/// @file A rigid body as the integrators see it: a rotor about a fixed or moving centre.
///
/// Every body turns about a rotation centre: its centre of mass when free, its pivot when
/// pivoted (a top). The integrators work in the principal frame of the inertia about that
/// centre (diagonal `moments`); `principal_to_body` carries orientations back to the body
/// frame the user modelled in. State: centre-of-mass position and velocity (ignored and
/// derived for pivoted bodies), orientation (principal frame to world) and world angular
/// momentum about the rotation centre.
///
/// Force terms are a list holding only what the scene asks for: a body without gravity,
/// torque or spring evaluates no force code at all on its step path.

#include <cmath>
#include <string>
#include <variant>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace tumble::engine {

/// Uniform gravity acting on the centre of mass (potential -m g . x).
struct Gravity {
  Eigen::Vector3d acceleration;  ///< m/s^2
};

/// A constant torque (not conservative: energy and |L| are not invariants with it).
struct ConstantTorque {
  Eigen::Vector3d torque;   ///< N m
  bool body_frame = false;  ///< true: fixed in the body (principal frame); false: in the world
};

/// A linear spring-damper from a world anchor to a body point.
struct Spring {
  Eigen::Vector3d anchor;  ///< world, m
  Eigen::Vector3d attach;  ///< body point relative to the rotation centre, principal frame, m
  double stiffness = 0.0;  ///< N/m
  double damping = 0.0;    ///< N s/m
};

using ForceTerm = std::variant<Gravity, ConstantTorque, Spring>;

/// The constant properties of one body.
struct BodyModel {
  std::string name;
  double mass = 1.0;                                  ///< kg
  Eigen::Vector3d moments = Eigen::Vector3d::Ones();  ///< principal, about the rotation centre
  Eigen::Quaterniond principal_to_body = Eigen::Quaterniond::Identity();
  bool pivoted = false;
  Eigen::Vector3d pivot = Eigen::Vector3d::Zero();  ///< world position of the pivot
  Eigen::Vector3d center_offset =
      Eigen::Vector3d::Zero();    ///< centre of mass minus rotation centre, principal frame
  std::vector<ForceTerm> forces;  ///< only the terms the scene asks for

  /// True when nothing exerts a torque about the rotation centre (the exact solution applies).
  bool torque_free() const;
  /// True when every force term is conservative (energy is an invariant).
  bool conservative() const;
};

/// The evolving state of one body.
struct BodyState {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();               ///< centre of mass, world
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();               ///< of the centre of mass
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  ///< principal frame to world
  Eigen::Vector3d angular_momentum = Eigen::Vector3d::Zero();  ///< world, about the rotation centre

  bool finite() const;
};

/// Net force on the centre of mass and torque about the rotation centre, world frame.
struct Wrench {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();
};

/// World angular velocity w = R J^-1 R^T L.
Eigen::Vector3d angular_velocity(const BodyModel& body, const BodyState& state);

/// A state at the origin, at rest in translation, with principal frame `orientation` (to the
/// world; normalised here) turning at `omega_principal` (rad/s, principal axes): L = R J w.
BodyState spinning_state(const BodyModel& body, const Eigen::Quaterniond& orientation,
                         const Eigen::Vector3d& omega_principal);

/// The wrench of the body's force terms in `state` (zero, and nothing evaluated, when it has
/// none). `omega` is the world angular velocity (for damping at a body point).
Wrench wrench(const BodyModel& body, const BodyState& state, const Eigen::Vector3d& omega);

/// Kinetic plus potential energy (gravity, springs), J.
double energy(const BodyModel& body, const BodyState& state);

/// The quantities a run watches for drift: energy (invariant when the body is conservative)
/// and |L| (invariant when it is torque-free).
struct Invariants {
  double energy = 0.0;    ///< kinetic plus potential, J (as energy())
  double momentum = 0.0;  ///< |L| about the rotation centre, kg m^2/s
};

/// Energy and |L| of one body.
Invariants invariants(const BodyModel& body, const BodyState& state);

/// Which bodies a sum of invariants takes.
enum class InvariantSum {
  kAll,             ///< every body's energy and |L|
  kWhereConserved,  ///< energy of the conservative bodies, |L| of the torque-free ones
};

/// Energy and |L| summed over the bodies, in body order (states[i] belongs to bodies[i]).
Invariants total_invariants(const std::vector<BodyModel>& bodies,
                            const std::vector<BodyState>& states,
                            InvariantSum which = InvariantSum::kAll);

/// World position of the point the body turns about: its pivot when pivoted, otherwise its
/// centre of mass.
Eigen::Vector3d rotation_centre(const BodyModel& body, const BodyState& state);

/// For a pivoted body, places the centre of mass from the orientation: x = pivot + R c,
/// v = w x R c. Does nothing for a free body.
void update_pivot_kinematics(const BodyModel& body, BodyState& state);

/// Orientation of the user's body frame (body to world) from the principal orientation.
Eigen::Quaterniond body_orientation(const BodyModel& body, const BodyState& state);

/// cos(x) and sin(x)/x of a half angle x, from x^2. Below |x| = 0.05 (every step that turns a
/// body by less than 0.1 rad) a Taylor polynomial gives both to rounding (the first omitted
/// terms are below 1e-20) with no square root or libm call; above it, std::cos and std::sin.
/// `cos_minus_one` is cos(x) - 1 to relative rounding (not 1 - cos rounded near 1): what a
/// compensated update (engine/src/compensated_orientation.hpp) adds to a quaternion.
struct HalfAngle {
  double cos;
  double sinc;           ///< sin(x) / x
  double cos_minus_one;  ///< cos(x) - 1, accurate to rounding relative to itself
};
inline HalfAngle half_angle(double x_squared) {
  if (x_squared < 0.0025) {
    const double y = x_squared;
    const double cos_minus_one =
        -y / 2.0 * (1.0 - y / 12.0 * (1.0 - y / 30.0 * (1.0 - y / 56.0 * (1.0 - y / 90.0))));
    return {1.0 + cos_minus_one,
            1.0 - y / 6.0 * (1.0 - y / 20.0 * (1.0 - y / 42.0 * (1.0 - y / 72.0))), cos_minus_one};
  }
  const double x = std::sqrt(x_squared);
  const double sin_half = std::sin(0.5 * x);
  return {std::cos(x), std::sin(x) / x, -2.0 * sin_half * sin_half};
}

/// Unit quaternion exp(rotation_vector / 2): a turn by |v| about v.
inline Eigen::Quaterniond rotation_quaternion(const Eigen::Vector3d& rotation_vector) {
  const HalfAngle h = half_angle(0.25 * rotation_vector.squaredNorm());
  const Eigen::Vector3d v = (0.5 * h.sinc) * rotation_vector;
  return Eigen::Quaterniond(h.cos, v.x(), v.y(), v.z());
}

/// q / |q| for a quaternion that is unit to within rounding (as after a product of unit
/// quaternions): one Newton step for 1/sqrt(|q|^2) is then exact to rounding, without a square
/// root or a division. Farther from unit length it falls back to a true normalisation.
inline Eigen::Quaterniond renormalized(const Eigen::Quaterniond& q) {
  const double norm_squared = q.squaredNorm();
  if (!(std::abs(norm_squared - 1.0) < 1e-8)) return q.normalized();
  return Eigen::Quaterniond(q.coeffs() * (1.5 - 0.5 * norm_squared));
}

/// Geodesic angle between two orientations, 2 atan2(|vec(a^* b)|, |w(a^* b)|) (handles q ~ -q;
/// accurate for tiny angles, unlike acos).
double orientation_angle(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b);

/// An energy scale of the motion that depends neither on where the origin is nor on a
/// potential's zero (engine/PHYSICS.md §6): the kinetic energy plus each potential's available
/// swing, from `state` over a run of `duration` s. Springs: k/2 |P - a|^2 (their minimum is 0).
/// Gravity on a pivoted body: U - U_min = m |g| l - m g . (R c), in [0, 2 m |g| l]. Gravity on
/// a free body without springs: the translational kinetic energy is replaced by the largest the
/// exact fall reaches over the run, m/2 max(|v|^2, |v + g duration|^2); with springs (total
/// stiffness K) gravity adds its sag energy m^2 |g|^2 / K. Zero only for a body at rest with
/// nothing to release.
double energy_scale(const BodyModel& body, const BodyState& state, double duration);

}  // namespace tumble::engine
