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
// (1978)): exp gives [[e^(Mt), int_0^t e^(Ms) ds b], [0, 1]]. With a single damped spring (a
// scene's case) M has rank 3 and the flow comes from phi functions of a symmetric 3 x 3
// matrix instead (one_spring_flow), several times cheaper. An exact flow is symmetric
// (its flow over -t is its inverse), so the kick-drift-kick compositions stay symmetric, and
// Strang splitting keeps order 2 and Yoshida's triple jump order 4 with damping.
#include "damped_kick.hpp"

#include <cmath>

#include <Eigen/Eigenvalues>
#include <unsupported/Eigen/MatrixFunctions>

#include "steppers.hpp"

namespace tumble::engine::steppers {
namespace {

Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

/// What the kick at s needs: the wrench with the body at rest (no velocity-dependent force),
/// which is b, and A = R J^-1 R^T.
struct KickParts {
  Wrench constant;
  Eigen::Matrix3d inverse_inertia;
};

KickParts kick_parts(const BodyModel& body, const BodyState& s) {
  BodyState at_rest = s;
  at_rest.velocity.setZero();
  at_rest.angular_momentum.setZero();
  const Eigen::Matrix3d rotation = s.orientation.toRotationMatrix();
  return {wrench(body, at_rest, Eigen::Vector3d::Zero()),
          rotation * body.moments.cwiseInverse().asDiagonal() * rotation.transpose()};
}

/// The augmented matrix [[M, b], [0, 0]] of the kick at s: free, y = (v, L, 1) (7); pivoted,
/// y = (L, 1) (4, top-left).
Eigen::Matrix<double, 7, 7> kick_matrix(const BodyModel& body, const BodyState& s,
                                        const KickParts& parts) {
  Eigen::Matrix<double, 7, 7> a = Eigen::Matrix<double, 7, 7>::Zero();
  const int l = body.pivoted ? 0 : 3;  // where L starts
  const Eigen::Matrix3d& inverse_inertia = parts.inverse_inertia;
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
    a.block<3, 1>(0, 3) = parts.constant.torque;
  } else {
    a.block<3, 1>(0, 6) = parts.constant.force / body.mass;
    a.block<3, 1>(3, 6) = parts.constant.torque;
  }
  return a;
}

/// phi1(z) = (e^z - 1) / z and phi2(z) = (e^z - 1 - z) / z^2 of a scalar, to rounding near 0 too.
Eigen::Vector2d phi_functions(double z) {
  if (std::abs(z) < 0.5) {
    // phi_k(z) = sum_j z^j / (j + k)!; 18 terms leave below 1e-17 at |z| = 0.5.
    double term1 = 1.0, term2 = 0.5, phi1 = 0.0, phi2 = 0.0;
    for (int j = 0; j < 18; ++j) {
      phi1 += term1;
      phi2 += term2;
      term1 *= z / (j + 2);
      term2 *= z / (j + 3);
    }
    return {phi1, phi2};
  }
  const double e = std::expm1(z);
  return {e / z, (e - z) / (z * z)};
}

/// phi1(Z) and phi2(Z) of a symmetric 3 x 3 Z: the Taylor series while |Z|_1 < 0.5 (the usual
/// kick: stopped once the next term is below 1e-17, a few terms for a small step), otherwise
/// from the eigenvalues.
void phi_matrices(const Eigen::Matrix3d& z, Eigen::Matrix3d& phi1, Eigen::Matrix3d& phi2) {
  const double norm = z.cwiseAbs().colwise().sum().maxCoeff();
  if (norm < 0.5) {
    Eigen::Matrix3d power = Eigen::Matrix3d::Identity();
    phi1 = power;
    phi2 = 0.5 * power;
    double factor1 = 1.0, factor2 = 0.5, bound = 1.0;  // 1/(j+1)!, 1/(j+2)!, norm^j
    for (int j = 1; j < 20 && bound * factor1 > 1e-17; ++j) {
      power = power * z;
      factor1 /= j + 1;
      factor2 /= j + 2;
      bound *= norm;
      phi1 += factor1 * power;
      phi2 += factor2 * power;
    }
    return;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(0.5 * (z + z.transpose()));
  Eigen::Vector3d values1, values2;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector2d phi = phi_functions(eigen.eigenvalues()[i]);
    values1[i] = phi[0];
    values2[i] = phi[1];
  }
  const Eigen::Matrix3d& v = eigen.eigenvectors();
  phi1 = v * values1.asDiagonal() * v.transpose();
  phi2 = v * values2.asDiagonal() * v.transpose();
}

/// The flow of one damped spring without the matrix exponential. M = U G has rank 3: free,
/// U = [I/m; X], G = -c [I, -X A]; pivoted, U = X, G = c X A (X = [r]x). Then
/// exp(t M) = I + t U phi1(t S) G and t phi1(t M) b = t b + t^2 U phi2(t S) G b with
/// S = G U = -c (I/m - X A X) or c X A X, symmetric (X A X is, as X^T = -X).
void one_spring_flow(const BodyModel& body, const BodyState& s, const Spring& spring, double t,
                     const KickParts& parts, Eigen::Matrix<double, 7, 7>& flow) {
  const Eigen::Matrix3d arm = cross_matrix(s.orientation * spring.attach);
  const double c = spring.damping;
  const Eigen::Matrix3d arm_a = arm * parts.inverse_inertia;
  Eigen::Matrix3d sym = c * arm_a * arm;
  if (!body.pivoted) sym.diagonal().array() -= c / body.mass;
  Eigen::Matrix3d phi1_s, phi2_s;
  phi_matrices(t * sym, phi1_s, phi2_s);
  if (body.pivoted) {
    const Eigen::Matrix3d g = c * arm_a;
    const Eigen::Vector3d& b = parts.constant.torque;
    flow.topLeftCorner<3, 3>() = Eigen::Matrix3d::Identity() + t * arm * phi1_s * g;
    flow.block<3, 1>(0, 3) = t * b + (t * t) * (arm * (phi2_s * (g * b)));
    return;
  }
  Eigen::Matrix<double, 6, 3> u;
  u << Eigen::Matrix3d::Identity() / body.mass, arm;
  Eigen::Matrix<double, 3, 6> g;
  g << -c * Eigen::Matrix3d::Identity(), c * arm_a;
  Eigen::Matrix<double, 6, 1> b;
  b << parts.constant.force / body.mass, parts.constant.torque;
  flow.topLeftCorner<6, 6>() = Eigen::Matrix<double, 6, 6>::Identity() + t * u * phi1_s * g;
  flow.block<6, 1>(0, 6) = t * b + (t * t) * (u * (phi2_s * (g * b)));
}

/// The one damped spring of the body, or null when it has several.
const Spring* only_damped_spring(const BodyModel& body) {
  const Spring* found = nullptr;
  for (const ForceTerm& term : body.forces) {
    const auto* spring = std::get_if<Spring>(&term);
    if (spring == nullptr || spring->damping == 0.0) continue;
    if (found != nullptr) return nullptr;
    found = spring;
  }
  return found;
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
    const KickParts parts = kick_parts(body, s);
    if (const Spring* spring = only_damped_spring(body)) {
      one_spring_flow(body, s, *spring, t, parts, flow.flow);
    } else {
      const Eigen::Matrix<double, 7, 7> a = kick_matrix(body, s, parts);
      if (body.pivoted) {
        flow.flow.topLeftCorner<4, 4>() = (t * a.topLeftCorner<4, 4>()).eval().exp();
      } else {
        flow.flow = (t * a).exp();
      }
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

void kick(const BodyModel& body, BodyState& s, double half_step, KickFlowCache* damped) {
  if (body.forces.empty()) return;
  if (damped != nullptr) {
    damped_kick(body, s, half_step, damped);
    return;
  }
  const Rates r = rates(body, s);
  s.velocity += half_step * r.acceleration;
  s.angular_momentum += half_step * r.torque;
}

}  // namespace tumble::engine::steppers
