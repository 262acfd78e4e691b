// The implicit midpoint rule, solved by Newton's method.
//
// midpoint is y1 = y0 + h f((y0 + y1) / 2) on y = (x, v, q, L_b) (13 numbers, q unnormalised):
// energy, |L| and |q| are quadratic invariants of the free body and a symmetric rule keeps all
// three exactly (Hairer, Lubich, Wanner, "Geometric Numerical Integration", 2006, ch. IV).
// The stage is solved by Newton's method with the analytic Jacobian of f (rate_jacobian), so
// the solve converges wherever Newton does, not only while h |df/dy| < 2 as a fixed-point
// iteration would: a linear spring is solved in one iteration at any step.
#include "implicit_midpoint.hpp"

#include <cmath>
#include <optional>

#include <Eigen/LU>

#include "steppers.hpp"

namespace tumble::engine::steppers {
namespace implicit_midpoint {
namespace {

Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

Eigen::Quaterniond quaternion_of(const Vector13& y) {
  return {y[6], y[7], y[8], y[9]};
}

/// d(n u)/dn, or d(n^* u)/dn when `inverse`, over n = (w, V) (3 x 4): Eigen rotates by the
/// polynomial n u = u + 2 w V x u + 2 V x (V x u) (n^*: V -> -V), exact for a unit n.
Eigen::Matrix<double, 3, 4> rotation_derivative(const Eigen::Quaterniond& n,
                                                const Eigen::Vector3d& u, bool inverse) {
  const double sign = inverse ? -1.0 : 1.0;
  const Eigen::Vector3d V = n.vec();
  Eigen::Matrix<double, 3, 4> d;
  d.col(0) = 2.0 * sign * V.cross(u);
  d.rightCols<3>() =
      -2.0 * sign * n.w() * cross_matrix(u) +
      2.0 * (V.dot(u) * Eigen::Matrix3d::Identity() + V * u.transpose() - 2.0 * u * V.transpose());
  return d;
}

/// Columns of the force Jacobian: x, v, the unit quaternion n, w_b.
constexpr int kX = 0, kV = 3, kN = 6, kW = 10;

/// Rows 0-2: d(F / m)/d(x, v, n, w_b) (world; free bodies only); rows 3-5: the same of the
/// body-frame torque R^T tau.
Eigen::Matrix<double, 6, 13> force_jacobian(const BodyModel& body, const Eigen::Vector3d& x,
                                            const Eigen::Vector3d& v, const Eigen::Quaterniond& n,
                                            const Eigen::Vector3d& omega_body) {
  Eigen::Matrix<double, 6, 13> g = Eigen::Matrix<double, 6, 13>::Zero();
  const Eigen::Matrix3d rotation = n.toRotationMatrix();
  for (const ForceTerm& term : body.forces) {
    if (const auto* gravity = std::get_if<Gravity>(&term)) {
      // Pivoted: R^T ((R c) x m g) = c x R^T (m g).
      if (body.pivoted) {
        g.block<3, 4>(3, kN) += cross_matrix(body.center_offset) *
                                rotation_derivative(n, body.mass * gravity->acceleration, true);
      }
    } else if (const auto* torque = std::get_if<ConstantTorque>(&term)) {
      // World: R^T tau; body frame: R^T R tau_b = tau_b, constant.
      if (!torque->body_frame) g.block<3, 4>(3, kN) += rotation_derivative(n, torque->torque, true);
    } else if (const auto* spring = std::get_if<Spring>(&term)) {
      // R^T F = -k (R^T (centre - anchor) + r) - c (w_b x r + R^T v), torque r x R^T F.
      const double k = spring->stiffness, c = spring->damping;
      const Eigen::Vector3d& r = spring->attach;
      const Eigen::Vector3d centre = body.pivoted ? body.pivot : x;
      Eigen::Matrix<double, 3, 13> force_body = Eigen::Matrix<double, 3, 13>::Zero();
      force_body.block<3, 4>(0, kN) = -k * rotation_derivative(n, centre - spring->anchor, true);
      force_body.block<3, 3>(0, kW) = c * cross_matrix(r);
      if (!body.pivoted) {
        force_body.block<3, 3>(0, kX) = -k * rotation.transpose();
        force_body.block<3, 3>(0, kV) = -c * rotation.transpose();
        force_body.block<3, 4>(0, kN) -= c * rotation_derivative(n, v, true);
        // F = -k (x + R r - anchor) - c (R (w_b x r) + v).
        const double per_mass = 1.0 / body.mass;
        g.block<3, 3>(0, kX).diagonal().array() -= k * per_mass;
        g.block<3, 3>(0, kV).diagonal().array() -= c * per_mass;
        g.block<3, 4>(0, kN) -= per_mass * (k * rotation_derivative(n, r, false) +
                                            c * rotation_derivative(n, omega_body.cross(r), false));
        g.block<3, 3>(0, kW) += (c * per_mass) * rotation * cross_matrix(r);
      }
      g.bottomRows<3>() += cross_matrix(r) * force_body;
    }
  }
  return g;
}

}  // namespace

Vector13 pack(const BodyState& s) {
  Vector13 y;
  y << s.position, s.velocity, s.orientation.w(), s.orientation.vec(),
      s.orientation.conjugate() * s.angular_momentum;
  return y;
}

Vector13 rate(const BodyModel& body, const Vector13& y) {
  const Eigen::Quaterniond q = quaternion_of(y);
  const Eigen::Vector3d momentum_body = y.segment<3>(10);
  BodyState state;
  state.position = y.segment<3>(0);
  state.velocity = y.segment<3>(3);
  state.orientation = q.normalized();
  state.angular_momentum = state.orientation * momentum_body;
  const Rates r = rates(body, state);
  const Eigen::Vector3d omega_body = momentum_body.cwiseQuotient(body.moments);
  const Eigen::Quaterniond turn =
      q * Eigen::Quaterniond(0.0, omega_body.x(), omega_body.y(), omega_body.z());
  Vector13 out;
  out << (body.pivoted ? Eigen::Vector3d::Zero() : state.velocity), r.acceleration, 0.5 * turn.w(),
      0.5 * turn.vec(), momentum_body.cross(omega_body) + state.orientation.conjugate() * r.torque;
  return out;
}

Matrix13 rate_jacobian(const BodyModel& body, const Vector13& y) {
  const Eigen::Vector4d q = y.segment<4>(6);
  const double length = q.norm();
  const Eigen::Vector4d unit = q / length;
  // d(q / |q|)/dq = (I - n n^T) / |q|.
  const Eigen::Matrix4d normalise =
      (Eigen::Matrix4d::Identity() - unit * unit.transpose()) / length;
  const Eigen::Vector3d momentum_body = y.segment<3>(10);
  const Eigen::Vector3d inverse_moments = body.moments.cwiseInverse();
  const Eigen::Vector3d omega = inverse_moments.cwiseProduct(momentum_body);
  const Eigen::Matrix3d per_moment = inverse_moments.asDiagonal();

  Matrix13 d = Matrix13::Zero();
  if (!body.pivoted) d.block<3, 3>(0, 3).setIdentity();
  // dq/dt = 1/2 q (0, w): (w, Q)(0, w) = (-Q . w, w_0 w + Q x w).
  Eigen::Matrix4d by_q;
  by_q << 0.0, -omega.transpose(), omega, -cross_matrix(omega);
  Eigen::Matrix<double, 4, 3> by_omega;
  by_omega << -q.tail<3>().transpose(),
      q[0] * Eigen::Matrix3d::Identity() + cross_matrix(q.tail<3>());
  d.block<4, 4>(6, 6) = 0.5 * by_q;
  d.block<4, 3>(6, 10) = 0.5 * by_omega * per_moment;
  // Gyroscopic term L_b x J^-1 L_b.
  d.block<3, 3>(10, 10) = cross_matrix(momentum_body) * per_moment - cross_matrix(omega);
  if (body.forces.empty()) return d;

  const Eigen::Quaterniond n(unit[0], unit[1], unit[2], unit[3]);
  const Eigen::Matrix<double, 6, 13> g =
      force_jacobian(body, y.segment<3>(0), y.segment<3>(3), n, omega);
  for (const auto& [row, from] : {std::pair{3, 0}, std::pair{10, 3}}) {
    if (row == 3 && body.pivoted) continue;  // the pivot holds the centre of mass
    d.block<3, 3>(row, 0) += g.block<3, 3>(from, kX);
    d.block<3, 3>(row, 3) += g.block<3, 3>(from, kV);
    d.block<3, 4>(row, 6) += g.block<3, 4>(from, kN) * normalise;
    d.block<3, 3>(row, 10) += g.block<3, 3>(from, kW) * per_moment;
  }
  return d;
}

}  // namespace implicit_midpoint

namespace {

/// The factorised Newton matrix I - h/2 df/dy. Only a spring on a free body couples the
/// translation (x, v) with the rotation (q, L_b) in df/dy; without one the matrix is block
/// diagonal, the rotation block is factorised alone (7 x 7 instead of 13 x 13, several times
/// cheaper), and the translation block, [[I, -h/2 I], [0, I]] (free: dx/dt = v, dv/dt
/// constant) or I (pivoted: x and v are derived), is solved directly.
class NewtonMatrix {
 public:
  using Matrix13 = implicit_midpoint::Matrix13;
  using Vector13 = implicit_midpoint::Vector13;

  explicit NewtonMatrix(const BodyModel& body) : pivoted_(body.pivoted) {
    for (const ForceTerm& term : body.forces) {
      if (std::holds_alternative<Spring>(term) && !body.pivoted) coupled_ = true;
    }
  }
  void factorise(const Matrix13& jacobian, double h) {
    h_ = h;
    if (coupled_) {
      full_.compute(Matrix13::Identity() - (0.5 * h) * jacobian);
    } else {
      rotation_.compute(Eigen::Matrix<double, 7, 7>::Identity() -
                        (0.5 * h) * jacobian.bottomRightCorner<7, 7>());
    }
  }
  Vector13 solve(const Vector13& residual) const {
    if (coupled_) return full_.solve(residual);
    Vector13 delta;
    delta.tail<7>() = rotation_.solve(residual.tail<7>());
    delta.segment<3>(3) = residual.segment<3>(3);
    delta.head<3>() = residual.head<3>() + (pivoted_ ? 0.0 : 0.5 * h_) * delta.segment<3>(3);
    return delta;
  }

 private:
  bool pivoted_;
  bool coupled_ = false;
  double h_ = 0.0;
  Eigen::PartialPivLU<Matrix13> full_;
  Eigen::PartialPivLU<Eigen::Matrix<double, 7, 7>> rotation_;
};

class Midpoint final : public BodyStepper {
 public:
  explicit Midpoint(const BodyModel& body) : body_(body), newton_matrix_(body) {}
  void step(BodyState& s, double, double h) override {
    using implicit_midpoint::Vector13;
    ++steps_;
    const Vector13 y0 = implicit_midpoint::pack(s);
    // Newton on g(y) = y - y0 - h f((y0 + y) / 2), dg/dy = I - h/2 df/dy, from y = y0. The
    // factorised dg/dy is kept while the updates shrink at least tenfold an iteration (a
    // simplified Newton step, Hairer and Wanner, "Solving ODEs II", 1996, IV.8: at small steps
    // the Jacobian barely changes over the solve) and evaluated afresh at the current iterate
    // otherwise. Stop once the update is at rounding level: below 1e-14 of the state (the
    // error left after it is far smaller), or the error it leaves estimated below 1e-16 of the
    // state, or no longer shrinking while below 1e-10 of it (rounding noise of an
    // ill-conditioned solve). A solve that does not converge (its last
    // update above 1e-9 of the state after kMaxIterations) or reaches a non-finite state hands
    // back NaN, which the simulation reports.
    Vector13 y = y0;
    bool refresh = true;
    double last_change = INFINITY;
    bool converged = false;
    for (int iteration = 0; iteration < kMaxIterations && !converged; ++iteration) {
      const Vector13 mid = 0.5 * (y0 + y);
      const Vector13 residual = y - y0 - h * implicit_midpoint::rate(body_, mid);
      if (refresh) {
        newton_matrix_.factorise(implicit_midpoint::rate_jacobian(body_, mid), h);
        ++jacobian_evaluations_;
      }
      const Vector13 delta = newton_matrix_.solve(residual);
      y -= delta;
      ++newton_iterations_;
      const double change = delta.lpNorm<Eigen::Infinity>();
      const double scale = y.lpNorm<Eigen::Infinity>();
      // The error left after an update contracting by theta is about theta / (1 - theta) of
      // it (Hairer and Wanner, IV.8).
      const double theta = iteration > 0 ? change / last_change : 1.0;
      converged = change <= 1e-14 * scale ||
                  (theta < 0.5 && theta / (1.0 - theta) * change <= 1e-16 * scale) ||
                  (change >= last_change && change <= 1e-10 * scale);
      refresh = !(change <= 0.1 * last_change);
      last_change = change;
    }
    if (!(converged || last_change <= 1e-9 * y.lpNorm<Eigen::Infinity>()) || !y.allFinite())
      y.setConstant(NAN);
    if (!body_.pivoted) {
      s.position = y.segment<3>(0);
      s.velocity = y.segment<3>(3);
    }
    s.orientation = Eigen::Quaterniond(y[6], y[7], y[8], y[9]).normalized();
    s.angular_momentum = s.orientation * Eigen::Vector3d(y.segment<3>(10));
  }

  /// Newton iterations, and evaluations (with factorisation) of the Jacobian, over every step
  /// so far.
  long long newton_iterations() const { return newton_iterations_; }
  long long jacobian_evaluations() const { return jacobian_evaluations_; }
  /// One right-hand-side evaluation per Newton iteration (the residual at the midpoint);
  /// the Jacobian's evaluations are not counted (engine/PHYSICS.md §5).
  std::optional<StepCounts> counts() const override {
    return StepCounts{steps_, 0, static_cast<std::size_t>(newton_iterations_)};
  }

 private:
  static constexpr int kMaxIterations = 50;

  const BodyModel& body_;
  NewtonMatrix newton_matrix_;
  long long newton_iterations_ = 0;
  long long jacobian_evaluations_ = 0;
  std::size_t steps_ = 0;
};

}  // namespace

std::unique_ptr<BodyStepper> make_midpoint(const BodyModel& body) {
  return std::make_unique<Midpoint>(body);
}

}  // namespace tumble::engine::steppers
