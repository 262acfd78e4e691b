// The Runge-Kutta family: rk4 (on the rotation group), implicit midpoint, adaptive dopri.
//
// rk4 is the Runge-Kutta-Munthe-Kaas method (Munthe-Kaas, "High order Runge-Kutta methods on
// manifolds", Appl. Numer. Math. 29 (1999)) with the classical tableau: the orientation is
// q(t) = exp(Theta(t)) q_n and Theta obeys Theta' = dexp^-1_Theta(w), with the inverse
// differential of the exponential truncated after the terms that order 4 needs:
// dexp^-1_Theta(w) = w - 1/2 Theta x w + 1/12 Theta x (Theta x w). Each stage turns q by an
// exponential map, so the method is 4th order in orientation, unlike RK4 on Euler angles or
// a quaternion update followed by normalisation of a 2nd-order rotation.
//
// midpoint is the implicit midpoint rule on (x, v, q, L_body): energy, |L| and |q| are
// quadratic invariants of the free body and it keeps all three exactly; solved by fixed-point
// iteration to rounding.
//
// dopri is Dormand and Prince's embedded 5(4) pair (J. Comput. Appl. Math. 6 (1980)) on
// (x, v, q, L) with q as four numbers, renormalised after each accepted step, and the usual
// step-size control; each call integrates exactly to the end of the output step.
#include <algorithm>
#include <cmath>

#include "compensated_orientation.hpp"
#include "steppers.hpp"

namespace tumble::engine::steppers {
namespace {

Eigen::Vector3d dexp_inverse(const Eigen::Vector3d& theta, const Eigen::Vector3d& w) {
  const Eigen::Vector3d theta_w = theta.cross(w);
  return w - 0.5 * theta_w + theta.cross(theta_w) / 12.0;
}

class Rk4 final : public BodyStepper {
 public:
  explicit Rk4(const BodyModel& body)
      : body_(body), inverse_moments_(body.moments.cwiseInverse()) {}
  void step(BodyState& s, double, double h) override {
    const bool moves = !body_.pivoted;
    BodyState stage = s;
    const auto at = [&](double fraction, const Rates& k, const Eigen::Vector3d& theta) {
      if (moves) {
        stage.position = s.position + fraction * h * k.velocity;
        stage.velocity = s.velocity + fraction * h * k.acceleration;
      }
      stage.angular_momentum = s.angular_momentum + fraction * h * k.torque;
      stage.orientation = rotation_quaternion(theta) * s.orientation;
    };
    const Rates k1 = rates(body_, s, inverse_moments_);
    const Eigen::Vector3d u1 = k1.omega;

    at(0.5, k1, 0.5 * h * u1);
    const Rates k2 = rates(body_, stage, inverse_moments_);
    const Eigen::Vector3d u2 = dexp_inverse(0.5 * h * u1, k2.omega);

    at(0.5, k2, 0.5 * h * u2);
    const Rates k3 = rates(body_, stage, inverse_moments_);
    const Eigen::Vector3d u3 = dexp_inverse(0.5 * h * u2, k3.omega);

    at(1.0, k3, h * u3);
    const Rates k4 = rates(body_, stage, inverse_moments_);
    const Eigen::Vector3d u4 = dexp_inverse(h * u3, k4.omega);

    const double sixth = h / 6.0;
    if (moves) {
      s.position += sixth * (k1.velocity + 2.0 * (k2.velocity + k3.velocity) + k4.velocity);
      s.velocity +=
          sixth * (k1.acceleration + 2.0 * (k2.acceleration + k3.acceleration) + k4.acceleration);
    }
    s.angular_momentum += sixth * (k1.torque + 2.0 * (k2.torque + k3.torque) + k4.torque);
    s.orientation = turned(s.orientation, sixth * (u1 + 2.0 * (u2 + u3) + u4));
  }

 private:
  /// exp(theta / 2) q, with the rounding of each step relative to the turn, not to q
  /// (compensated_orientation.hpp).
  Eigen::Quaterniond turned(const Eigen::Quaterniond& q, const Eigen::Vector3d& theta) {
    orientation_.resume(q);
    orientation_.turn_world(small_turn(theta));
    return orientation_.value();
  }

  const BodyModel& body_;
  Eigen::Vector3d inverse_moments_;
  CompensatedOrientation orientation_;
};

/// (x, v, q, L) as 13 numbers, q stored w, x, y, z.
using Vector13 = Eigen::Matrix<double, 13, 1>;

Vector13 pack(const BodyState& s, const Eigen::Vector3d& momentum) {
  Vector13 y;
  y << s.position, s.velocity, s.orientation.w(), s.orientation.vec(), momentum;
  return y;
}

Eigen::Quaterniond quaternion_of(const Vector13& y) {
  return {y[6], y[7], y[8], y[9]};
}

/// dq/dt for q (not necessarily unit) turning at angular velocity w (world: w q, body: q w).
Eigen::Vector4d quaternion_rate(const Eigen::Quaterniond& q, const Eigen::Vector3d& w, bool body) {
  const Eigen::Quaterniond pure(0.0, w.x(), w.y(), w.z());
  const Eigen::Quaterniond product = body ? q * pure : pure * q;
  return 0.5 * Eigen::Vector4d(product.w(), product.x(), product.y(), product.z());
}

class Midpoint final : public BodyStepper {
 public:
  explicit Midpoint(const BodyModel& body) : body_(body) {}
  void step(BodyState& s, double, double h) override {
    // Unknowns: x, v, q, and the body-frame momentum L_b.
    const Vector13 y0 = pack(s, s.orientation.conjugate() * s.angular_momentum);
    // Fixed-point iteration y <- y0 + h f((y0 + y)/2); it contracts by about h |df/dy| / 2 a
    // sweep. The change need not shrink every sweep (for an oscillator the iteration error
    // turns as it shrinks), so stop only once it is at rounding level: below 1e-15 of the
    // state, or no longer shrinking while below 1e-12 of it (rounding noise).
    // Near the edge of its convergence (h |df/dy| / 2 -> 1) it needs many sweeps; a solve that
    // does not converge hands back a non-finite state, which the simulation reports.
    Vector13 y = y0 + h * rate(y0);
    double last_change = INFINITY;
    bool converged = false;
    for (int iteration = 0; iteration < 4000 && !converged; ++iteration) {
      const Vector13 next = y0 + h * rate(0.5 * (y0 + y));
      const double change = (next - y).lpNorm<Eigen::Infinity>();
      const double scale = next.lpNorm<Eigen::Infinity>();
      y = next;
      converged = !(change > 1e-15 * scale) || (change >= last_change && change <= 1e-12 * scale);
      last_change = change;
    }
    if (!converged && !(last_change <= 1e-9 * y.lpNorm<Eigen::Infinity>())) y.setConstant(NAN);
    if (!body_.pivoted) {
      s.position = y.segment<3>(0);
      s.velocity = y.segment<3>(3);
    }
    s.orientation = quaternion_of(y).normalized();
    s.angular_momentum = s.orientation * Eigen::Vector3d(y.segment<3>(10));
  }

 private:
  Vector13 rate(const Vector13& y) const {
    const Eigen::Quaterniond q = quaternion_of(y);
    const Eigen::Vector3d momentum_body = y.segment<3>(10);
    BodyState state;
    state.position = y.segment<3>(0);
    state.velocity = y.segment<3>(3);
    state.orientation = q.normalized();
    state.angular_momentum = state.orientation * momentum_body;
    const Rates r = rates(body_, state);
    const Eigen::Vector3d omega_body = momentum_body.cwiseQuotient(body_.moments);
    Vector13 out;
    out << (body_.pivoted ? Eigen::Vector3d::Zero() : state.velocity), r.acceleration,
        quaternion_rate(q, omega_body, true),
        momentum_body.cross(omega_body) + state.orientation.conjugate() * r.torque;
    return out;
  }

  const BodyModel& body_;
};

class Dopri final : public BodyStepper {
 public:
  Dopri(const BodyModel& body, double tolerance) : body_(body), tolerance_(tolerance) {}

  void step(BodyState& s, double, double h) override {
    Vector13 y = pack(s, s.angular_momentum);
    if (!(step_ > 0.0)) step_ = initial_step(y, h);
    double done = 0.0;
    for (int attempts = 0; done < h && attempts < 1'000'000; ++attempts) {
      const double remaining = h - done;
      const double trial = std::min(step_, remaining);
      Vector13 next, error;
      attempt(y, trial, next, error);
      // Mixed absolute/relative error norm (RMS over the components).
      double sum = 0.0;
      for (int i = 0; i < 13; ++i) {
        const double scale = tolerance_ * (1.0 + std::max(std::abs(y[i]), std::abs(next[i])));
        sum += (error[i] / scale) * (error[i] / scale);
      }
      const double norm = std::sqrt(sum / 13.0);
      if (!std::isfinite(norm)) {  // a non-finite state: hand it back for detection
        y = next;
        break;
      }
      if (norm <= 1.0) {
        done = trial < remaining ? done + trial : h;
        y = next;
        const Eigen::Quaterniond q = quaternion_of(y).normalized();
        y.segment<4>(6) << q.w(), q.x(), q.y(), q.z();
      }
      // Standard controller: safety 0.9, growth between 0.2x and 5x.
      const double factor = norm == 0.0 ? 5.0 : std::clamp(0.9 * std::pow(norm, -0.2), 0.2, 5.0);
      if (norm <= 1.0 && trial < step_) continue;  // a short last step says nothing of step_
      step_ = trial * factor;
    }
    // A step size that collapsed to nothing: hand back a non-finite state to be reported.
    if (done < h) y.setConstant(NAN);
    if (!body_.pivoted) {
      s.position = y.segment<3>(0);
      s.velocity = y.segment<3>(3);
    }
    s.orientation = quaternion_of(y).normalized();
    s.angular_momentum = y.segment<3>(10);
  }

 private:
  Vector13 rate(const Vector13& y) const {
    BodyState state;
    state.position = y.segment<3>(0);
    state.velocity = y.segment<3>(3);
    state.orientation = quaternion_of(y).normalized();
    state.angular_momentum = y.segment<3>(10);
    const Rates r = rates(body_, state);
    Vector13 out;
    out << (body_.pivoted ? Eigen::Vector3d::Zero() : state.velocity), r.acceleration,
        quaternion_rate(quaternion_of(y), r.omega, false), r.torque;
    return out;
  }

  double initial_step(const Vector13& y, double h) const {
    // A small fraction of a turn, and of the output step.
    const double spin = rate(y).segment<4>(6).norm() * 2.0;
    return std::min(h, spin > 0.0 ? 0.01 / spin : h);
  }

  void attempt(const Vector13& y, double h, Vector13& next, Vector13& error) const {
    // Dormand-Prince 5(4) tableau.
    const Vector13 k1 = rate(y);
    const Vector13 k2 = rate(y + h * (1.0 / 5.0) * k1);
    const Vector13 k3 = rate(y + h * ((3.0 / 40.0) * k1 + (9.0 / 40.0) * k2));
    const Vector13 k4 = rate(y + h * ((44.0 / 45.0) * k1 - (56.0 / 15.0) * k2 + (32.0 / 9.0) * k3));
    const Vector13 k5 = rate(y + h * ((19372.0 / 6561.0) * k1 - (25360.0 / 2187.0) * k2 +
                                      (64448.0 / 6561.0) * k3 - (212.0 / 729.0) * k4));
    const Vector13 k6 =
        rate(y + h * ((9017.0 / 3168.0) * k1 - (355.0 / 33.0) * k2 + (46732.0 / 5247.0) * k3 +
                      (49.0 / 176.0) * k4 - (5103.0 / 18656.0) * k5));
    next = y + h * ((35.0 / 384.0) * k1 + (500.0 / 1113.0) * k3 + (125.0 / 192.0) * k4 -
                    (2187.0 / 6784.0) * k5 + (11.0 / 84.0) * k6);
    const Vector13 k7 = rate(next);
    error = h * ((71.0 / 57600.0) * k1 - (71.0 / 16695.0) * k3 + (71.0 / 1920.0) * k4 -
                 (17253.0 / 339200.0) * k5 + (22.0 / 525.0) * k6 - (1.0 / 40.0) * k7);
  }

  const BodyModel& body_;
  double tolerance_;
  double step_ = 0.0;  ///< the controller's current step, kept across output steps
};

}  // namespace

std::unique_ptr<BodyStepper> make_rk4(const BodyModel& body) {
  return std::make_unique<Rk4>(body);
}
std::unique_ptr<BodyStepper> make_midpoint(const BodyModel& body) {
  return std::make_unique<Midpoint>(body);
}
std::unique_ptr<BodyStepper> make_dopri(const BodyModel& body, double tolerance) {
  return std::make_unique<Dopri>(body, tolerance);
}

}  // namespace tumble::engine::steppers
