// The kick of the splitting family with velocity-dependent forces.
//
// With x and q frozen, w = A L (A = R J^-1 R^T constant) and the point velocity of a spring's
// attachment is u = v + w x r = v - [r]x A L (r = R attach): every force term is affine in
// y = (v, L) (L alone for a pivoted body, whose v is derived). Summed over the springs,
//   dv/dt = b_v - (c/m) v + (c/m) [r]x A L,
//   dL/dt = b_L - c [r]x v + c [r]x [r]x A L,
// with (b_v, b_L) the acceleration and torque at v = 0, L = 0 (gravity, constant torques,
// spring stiffness). The kick is then a linear constant-coefficient ODE y' = M y + b, and its
// exact flow over t is the matrix exponential of the augmented matrix [[M, b], [0, 0]] t (Van
// Loan, "Computing integrals involving the matrix exponential", IEEE Trans. Automat. Control 23
// (1978)): exp gives [[e^(Mt), int_0^t e^(Ms) ds b], [0, 1]]. An exact flow is symmetric
// (its flow over -t is its inverse), so the kick-drift-kick compositions stay symmetric, and
// Strang splitting keeps order 2 and Yoshida's triple jump order 4 with damping.
#include "damped_kick.hpp"

#include <unsupported/Eigen/MatrixFunctions>

namespace tumble::engine::steppers {
namespace {

Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

/// The augmented matrix [[M, b], [0, 0]] of the kick at s: free, y = (v, L, 1) (7); pivoted,
/// y = (L, 1) (4, top-left).
Eigen::Matrix<double, 7, 7> kick_matrix(const BodyModel& body, const BodyState& s) {
  // The constant part: the wrench with the body at rest (no velocity-dependent force).
  BodyState at_rest = s;
  at_rest.velocity.setZero();
  at_rest.angular_momentum.setZero();
  const Wrench constant = wrench(body, at_rest, Eigen::Vector3d::Zero());
  const Eigen::Matrix3d rotation = s.orientation.toRotationMatrix();
  const Eigen::Matrix3d inverse_inertia =
      rotation * body.moments.cwiseInverse().asDiagonal() * rotation.transpose();
  Eigen::Matrix<double, 7, 7> a = Eigen::Matrix<double, 7, 7>::Zero();
  const int l = body.pivoted ? 0 : 3;  // where L starts
  for (const ForceTerm& term : body.forces) {
    const auto* spring = std::get_if<Spring>(&term);
    if (spring == nullptr || spring->damping == 0.0) continue;
    const Eigen::Matrix3d arm = cross_matrix(s.orientation * spring->attach);
    const double c = spring->damping;
    a.block<3, 3>(l, l) += c * arm * arm * inverse_inertia;
    if (body.pivoted) continue;  // v is derived: no translation
    a.block<3, 3>(0, 0).diagonal().array() -= c / body.mass;
    a.block<3, 3>(0, 3) += (c / body.mass) * arm * inverse_inertia;
    a.block<3, 3>(3, 0) -= c * arm;
  }
  if (body.pivoted) {
    a.block<3, 1>(0, 3) = constant.torque;
  } else {
    a.block<3, 1>(0, 6) = constant.force / body.mass;
    a.block<3, 1>(3, 6) = constant.torque;
  }
  return a;
}

}  // namespace

bool has_damping(const BodyModel& body) {
  for (const ForceTerm& term : body.forces) {
    if (const auto* spring = std::get_if<Spring>(&term); spring && spring->damping != 0.0)
      return true;
  }
  return false;
}

void damped_kick(const BodyModel& body, BodyState& s, double t, KickFlowCache* cache) {
  // The kick depends on t, q and (free bodies) x: the key of the cache, compared exactly.
  const Eigen::Vector4d orientation = s.orientation.coeffs();
  const Eigen::Vector3d position = body.pivoted ? Eigen::Vector3d::Zero() : s.position;
  KickFlowCache local;
  KickFlowCache& flow = cache != nullptr ? *cache : local;
  if (!(flow.valid && flow.t == t && flow.position == position &&
        flow.orientation == orientation)) {
    const Eigen::Matrix<double, 7, 7> a = kick_matrix(body, s);
    if (body.pivoted) {
      flow.flow.topLeftCorner<4, 4>() = (t * a.topLeftCorner<4, 4>()).eval().exp();
    } else {
      flow.flow = (t * a).exp();
    }
    flow.valid = true;
    flow.t = t;
    flow.position = position;
    flow.orientation = orientation;
  }
  if (body.pivoted) {
    s.angular_momentum =
        flow.flow.topLeftCorner<3, 3>() * s.angular_momentum + flow.flow.block<3, 1>(0, 3);
  } else {
    const Eigen::Matrix<double, 6, 1> y =
        flow.flow.topLeftCorner<6, 6>() *
            (Eigen::Matrix<double, 6, 1>() << s.velocity, s.angular_momentum).finished() +
        flow.flow.block<6, 1>(0, 6);
    s.velocity = y.head<3>();
    s.angular_momentum = y.tail<3>();
  }
}

}  // namespace tumble::engine::steppers
