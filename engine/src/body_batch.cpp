// Semi-implicit Euler over a structure of arrays of free bodies.
//
// The loop body is the scalar SemiImplicitEuler stepper (integrators.cpp) with the Eigen
// quaternion operations written out on doubles, in the same order of operations where it
// matters: the world-to-body rotation of L is Eigen's q^* v (v + w t + u x t, t = 2 u x v),
// the turn is rotation_quaternion's exp(h w / 2) with its Taylor branch below 1e-4 rad (a
// select, no branch), then the product and the normalisation (summed and grouped as Eigen's
// SSE code does, so the two agree to a few ulps; the remaining difference is multiplying by
// 1/J where the scalar stepper divides by J). No calls but sqrt, sin and cos, no aliasing
// between the arrays (restrict-qualified pointers).
#include "engine/body_batch.hpp"

#include <cmath>
#include <stdexcept>

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
    const double bx = (lx[i] + w * tx + (uy * tz - uz * ty)) * j1[i];
    const double by = (ly[i] + w * ty + (uz * tx - ux * tz)) * j2[i];
    const double bz = (lz[i] + w * tz + (ux * ty - uy * tx)) * j3[i];
    // World angular velocity w = q w_b (u = vec(q) now).
    const double sx = 2.0 * (qy[i] * bz - qz[i] * by);
    const double sy = 2.0 * (qz[i] * bx - qx[i] * bz);
    const double sz = 2.0 * (qx[i] * by - qy[i] * bx);
    const double ox = bx + w * sx + (qy[i] * sz - qz[i] * sy);
    const double oy = by + w * sy + (qz[i] * sx - qx[i] * sz);
    const double oz = bz + w * sz + (qx[i] * sy - qy[i] * sx);

    // Turn: r = exp(h w / 2) = (cos(a/2), sin(a/2)/a * h w), a = h |w|, with the same
    // half-angle functions as rotation_quaternion.
    const double rvx = h * ox, rvy = h * oy, rvz = h * oz;
    const HalfAngle turn = half_angle(0.25 * (rvx * rvx + rvy * rvy + rvz * rvz));
    const double rw = turn.cos;
    const double sinc_half = 0.5 * turn.sinc;
    const double rx = sinc_half * rvx, ry = sinc_half * rvy, rz = sinc_half * rvz;

    // q <- r q (grouped as Eigen's SSE quaternion product groups it), renormalised.
    const double nx = (rw * qx[i] + ry * qz[i]) - (rz * qy[i] - rx * w);
    const double ny = (rw * qy[i] + ry * w) + (rz * qx[i] - rx * qz[i]);
    const double nz = (rw * qz[i] - ry * qx[i]) + (rz * w + rx * qy[i]);
    const double nw = (rw * w - ry * qy[i]) - (rz * qz[i] + rx * qx[i]);
    const Eigen::Quaterniond q = renormalized(Eigen::Quaterniond(nw, nx, ny, nz));
    qw[i] = q.w();
    qx[i] = q.x();
    qy[i] = q.y();
    qz[i] = q.z();
  }
}

}  // namespace tumble::engine
