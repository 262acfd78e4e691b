// Semi-implicit Euler over a structure of arrays of free bodies.
//
// The loop body is the scalar SemiImplicitEuler stepper (integrators.cpp) on doubles: the
// kick and drift, the world-to-body rotation of L written out as Eigen's q^* v
// (v + w t + u x t, t = 2 u x v), then the same three principal-axis sub-rotations
// R1(h) R2(h) R3(h) (principal_rotation.hpp, inlined here; each a half_angle() polynomial or
// one sin and cos) and the same normalisation, so the two agree to a few ulps. No calls but
// sqrt, sin and cos, no aliasing between the arrays (restrict-qualified pointers).
#include "engine/dynamics/body_batch.hpp"

#include <cmath>
#include <stdexcept>

#include "principal_rotation.hpp"

namespace tumble::engine {

void FreeBodyBatch::add(const Eigen::Vector3d& moments, const BodyState& state) {
  if (!(moments.minCoeff() > 0.0) || !moments.allFinite()) {
    throw std::invalid_argument("FreeBodyBatch: principal moments must be positive and finite");
  }
  const Eigen::Quaterniond q = state.orientation.normalized();
  position_x.push_back(state.position.x());
  position_y.push_back(state.position.y());
  position_z.push_back(state.position.z());
  velocity_x.push_back(state.velocity.x());
  velocity_y.push_back(state.velocity.y());
  velocity_z.push_back(state.velocity.z());
  orientation_w.push_back(q.w());
  orientation_x.push_back(q.x());
  orientation_y.push_back(q.y());
  orientation_z.push_back(q.z());
  momentum_x.push_back(state.angular_momentum.x());
  momentum_y.push_back(state.angular_momentum.y());
  momentum_z.push_back(state.angular_momentum.z());
  inverse_moment_1.push_back(1.0 / moments.x());
  inverse_moment_2.push_back(1.0 / moments.y());
  inverse_moment_3.push_back(1.0 / moments.z());
}

BodyState FreeBodyBatch::state(std::size_t i) const {
  BodyState s;
  s.position = {position_x[i], position_y[i], position_z[i]};
  s.velocity = {velocity_x[i], velocity_y[i], velocity_z[i]};
  s.orientation =
      Eigen::Quaterniond(orientation_w[i], orientation_x[i], orientation_y[i], orientation_z[i]);
  s.angular_momentum = {momentum_x[i], momentum_y[i], momentum_z[i]};
  return s;
}

void step_semi_implicit_euler(FreeBodyBatch& batch, const Eigen::Vector3d& gravity, double h) {
  const std::size_t n = batch.size();
  double* __restrict px = batch.position_x.data();
  double* __restrict py = batch.position_y.data();
  double* __restrict pz = batch.position_z.data();
  double* __restrict vx = batch.velocity_x.data();
  double* __restrict vy = batch.velocity_y.data();
  double* __restrict vz = batch.velocity_z.data();
  double* __restrict qw = batch.orientation_w.data();
  double* __restrict qx = batch.orientation_x.data();
  double* __restrict qy = batch.orientation_y.data();
  double* __restrict qz = batch.orientation_z.data();
  const double* __restrict lx = batch.momentum_x.data();
  const double* __restrict ly = batch.momentum_y.data();
  const double* __restrict lz = batch.momentum_z.data();
  const double* __restrict j1 = batch.inverse_moment_1.data();
  const double* __restrict j2 = batch.inverse_moment_2.data();
  const double* __restrict j3 = batch.inverse_moment_3.data();
  const double hgx = h * gravity.x(), hgy = h * gravity.y(), hgz = h * gravity.z();

  for (std::size_t i = 0; i < n; ++i) {
    // Kick (L has no torque to take), then drift with the new velocity.
    vx[i] += hgx;
    vy[i] += hgy;
    vz[i] += hgz;
    px[i] += h * vx[i];
    py[i] += h * vy[i];
    pz[i] += h * vz[i];

    // Body-frame momentum: L_b = q^* L, as v + w t + u x t with u = -vec(q), t = 2 u x L.
    const double w = qw[i], ux = -qx[i], uy = -qy[i], uz = -qz[i];
    const double tx = 2.0 * (uy * lz[i] - uz * ly[i]);
    const double ty = 2.0 * (uz * lx[i] - ux * lz[i]);
    const double tz = 2.0 * (ux * ly[i] - uy * lx[i]);
    Eigen::Vector3d momentum(lx[i] + w * tx + (uy * tz - uz * ty),
                             ly[i] + w * ty + (uz * tx - ux * tz),
                             lz[i] + w * tz + (ux * ty - uy * tx));
    // The free rotation R1(h) R2(h) R3(h); world L is not touched.
    Eigen::Vector4d turned(w, qx[i], qy[i], qz[i]);
    const Eigen::Vector3d inverse_moments(j1[i], j2[i], j3[i]);
    for (int axis = 0; axis < 3; ++axis) {
      steppers::rotate_about_principal_axis(inverse_moments, axis, h, turned, momentum);
    }
    const Eigen::Quaterniond q =
        renormalized(Eigen::Quaterniond(turned[0], turned[1], turned[2], turned[3]));
    qw[i] = q.w();
    qx[i] = q.x();
    qy[i] = q.y();
    qz[i] = q.z();
  }
}

}  // namespace tumble::engine
