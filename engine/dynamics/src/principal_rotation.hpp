#pragma once
// Private to the engine: the exact flow of one term L_i^2 / (2 J_i) of the free kinetic energy,
// a rotation about principal axis i, shared by the splittings (rotation_splitting.cpp) and
// semi-implicit-euler (integrators.cpp) so that both compose the same sub-rotations.

#include <Eigen/Core>

#include "engine/body/rigid_body.hpp"

namespace tumble::engine::steppers {

/// Turns the body about principal `axis` (0, 1, 2) for time t: by +angle = t L_i / J_i, applied
/// on the right of `q` (w, x, y, z), while its body-frame `momentum` turns by -angle (world L
/// is untouched). One half_angle() (a polynomial for the usual small angles) per call.
inline void rotate_about_principal_axis(const Eigen::Vector3d& inverse_moments, int axis, double t,
                                        Eigen::Vector4d& q, Eigen::Vector3d& momentum) {
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
}

}  // namespace tumble::engine::steppers
