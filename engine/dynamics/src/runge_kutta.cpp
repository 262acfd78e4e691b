// The Runge-Kutta family: rk4 (on the rotation group), adaptive dopri (the implicit midpoint
// rule is in implicit_midpoint.cpp).
//
// rk4 is the Runge-Kutta-Munthe-Kaas method (Munthe-Kaas, "High order Runge-Kutta methods on
// manifolds", Appl. Numer. Math. 29 (1999)) with the classical tableau: the orientation is
// q(t) = exp(Theta(t)) q_n and Theta obeys Theta' = dexp^-1_Theta(w), with the inverse
// differential of the exponential truncated after the terms that order 4 needs:
// dexp^-1_Theta(w) = w - 1/2 Theta x w + 1/12 Theta x (Theta x w). Each stage turns q by an
// exponential map, so the method is 4th order in orientation, unlike RK4 on Euler angles or
// a quaternion update followed by normalisation of a 2nd-order rotation.
//
// dopri is Dormand and Prince's embedded 5(4) pair (J. Comput. Appl. Math. 6 (1980)) on
// (x, v, q, L) with q as four numbers, renormalised after each accepted step, and the usual
// step-size control. It takes its own steps whatever the output step, running ahead of the
// output time, and evaluates the output instants by its continuous extension (Hairer,
// Norsett, Wanner 1993, II.6), so that its step sequence does not depend on when it is asked.
//
// Its error norm (engine/PHYSICS.md §3) is the scaled norm of Hairer, Norsett and Wanner
// (1993, II.4, eq. 4.11), err_i / (atol + rtol |y_i|), in its maximum form, over the four
// quantities of a rigid body rather than over 13 raw numbers: the error vectors of x, v and L
// each against its own length (so a body whose |L| is 1e-4 kg m^2/s is held to rtol relative,
// not to an absolute 1e-10 that is 1e-6 of it, and the norm does not depend on how the world
// axes are turned), and the orientation as the rotation angle between the 5th- and 4th-order
// orientations (what is left of the quaternion's error once it is renormalised), against
// atol + rtol rad. Measured on the T-handle (engine/PHYSICS.md §3), the embedded estimate is
// accurate: within 15% of the true local error of the 4th-order solution, which itself is 10
// to 1000 times that of the 5th-order solution kept. What made the global error 1e6 times the
// tolerance was not the estimate but the energy drift it allowed: a non-symplectic method's
// energy error grows linearly in time, and near an intermediate-axis spin the flip times are
// hypersensitive to the energy. So for a torque-free body, whose rotational energy is an
// invariant, each accepted step is followed by one Newton step that turns q back onto the
// energy's level set (a standard projection method: Hairer, Lubich, Wanner, Geometric
// Numerical Integration, 2nd ed. 2006, IV.4; Shampine 1986): the energy is then kept to
// rounding, and the error grows linearly in time instead of quadratically.
#include <algorithm>
#include <array>
#include <cmath>

#include "compensated_orientation.hpp"
#include "steppers.hpp"

namespace tumble::engine::steppers {
namespace {

/// dopri's largest step as a turn, rad: the step never turns the body by more than this at its
/// current spin |w|. A maximal step size is part of Hairer's own DOPRI5 (Hairer, Norsett,
/// Wanner 1993, II.4 and its code's HMAX); here it is scaled by the spin so it means the same
/// for every body. Why: the estimate measures the 4th-order solution's error, and the step kept
/// is the 5th-order one's, far smaller only while h |w| is small; at loose tolerances the
/// controller reaches ~1 rad a step, where the two are comparable and the global error, the sum
/// of the steps' errors, is hundreds of tolerances (the heavy top at 1e-4: 457 with 1.1 rad a
/// step, 248 with 1.0, 25 with 0.7, 3.0 with 0.5; engine/PHYSICS.md §3). Tighter tolerances
/// take smaller steps and are untouched.
constexpr double kDopriMaxTurnPerStep = 0.5;

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

class Dopri final : public BodyStepper {
 public:
  Dopri(const BodyModel& body, const StepSettings& settings)
      : body_(body),
        rtol_(settings.tolerance),
        atol_(settings.absolute_tolerance),
        keeps_energy_(body.torque_free()) {}

  void step(BodyState& s, double t, double h) override {
    const double target = t + h;
    if (!continues(s, t)) restart(s, t, h);
    // Natural steps until the last accepted one reaches the output time, which is then
    // interpolated: the output step never shortens a step.
    bool good = true;
    for (int attempts = 0; good && t_ < target && attempts < 1'000'000; ++attempts) {
      good = advance();
    }
    Vector13 y = y_;
    if (!good || t_ < target) {
      // A non-finite step, or a step size that collapsed: a non-finite state to be reported.
      y.setConstant(NAN);
    } else if (target < t_) {
      y = interpolate(target);
    }
    if (!body_.pivoted) {
      s.position = y.segment<3>(0);
      s.velocity = y.segment<3>(3);
    }
    s.orientation = quaternion_of(y).normalized();
    s.angular_momentum = y.segment<3>(10);
    handed_ = s;
    handed_time_ = target;
    started_ = true;
  }

  std::optional<StepCounts> counts() const override {
    return StepCounts{accepted_, rejected_, evaluations_};
  }

 private:
  using Stages = std::array<Vector13, 7>;

  /// Whether `s` at `t` is what the last call handed back, so the internal state (which may be
  /// ahead of it) still applies. x and v of a pivoted body are derived from q and L after each
  /// step (update_pivot_kinematics) and are not integrated here, so they are not compared.
  bool continues(const BodyState& s, double t) const {
    if (!started_ || !(std::abs(t - handed_time_) <= 1e-12 * std::max(1.0, std::abs(t)))) {
      return false;
    }
    const bool moved =
        !body_.pivoted && (s.position != handed_.position || s.velocity != handed_.velocity);
    return !moved && s.orientation.coeffs() == handed_.orientation.coeffs() &&
           s.angular_momentum == handed_.angular_momentum;
  }

  /// Starts the integration afresh from `s` at `t` (the first call, or a state changed from
  /// outside); the controller's step size is kept.
  void restart(const BodyState& s, double t, double h) {
    y_ = pack(s, s.angular_momentum);
    t_ = t;
    k1_ = rate(y_);
    energy_ = rotational_energy(y_);
    if (!(step_ > 0.0)) {
      // A small fraction of a turn, and of the output step.
      const double spin = k1_.segment<4>(6).norm() * 2.0;
      step_ = std::min(h, spin > 0.0 ? 0.01 / spin : h);
    }
  }

  /// One attempt from (t_, y_) with the current step size; on acceptance the interval
  /// [t_, t_ + step] becomes the one interpolated. False on a non-finite error estimate.
  bool advance() {
    const double h = step_;
    Stages k;
    k[0] = k1_;
    Vector13 next, error;
    attempt(y_, h, k, next, error);
    const double norm = error_norm(next, error);
    if (!std::isfinite(norm)) return false;
    if (norm <= 1.0) {
      ++accepted_;
      keep_interpolant(h, k, next);
      t_ += h;
      // q renormalised; f is linear in q's four numbers at a given unit q (w depends on q/|q|
      // only), so the last stage rescaled is exactly the first stage at the renormalised state.
      const double length = quaternion_of(next).norm();
      y_ = next;
      y_.segment<4>(6) /= length;
      k1_ = k[6];
      k1_.segment<4>(6) /= length;
      if (keeps_energy_ && restore_energy()) k1_ = rate(y_);
    } else {
      ++rejected_;
    }
    // Standard controller: safety 0.9, growth between 0.2x and 5x.
    step_ = h * (norm == 0.0 ? 5.0 : std::clamp(0.9 * std::pow(norm, -0.2), 0.2, 5.0));
    // At most kDopriMaxTurnPerStep of turn at the current spin (|dq/dt| = |w| / 2 at unit q).
    const double spin = 2.0 * k1_.segment<4>(6).norm();
    if (spin * step_ > kDopriMaxTurnPerStep) step_ = kDopriMaxTurnPerStep / spin;
    return true;
  }

  /// The error of an attempt from y_ to `next` against its tolerance, <= 1 to accept (Hairer,
  /// Norsett, Wanner 1993, II.4, eq. 4.11, maximum form): max over x, v, L of |err| / (atol +
  /// rtol max(|y|, |next|)) (3-vectors, Euclidean length) and the orientation's error angle /
  /// (atol + rtol 1 rad). An error of exactly 0 counts 0 whatever its scale (x and v of a pivoted
  /// body, L of a torque-free one); a non-finite one gives NaN.
  double error_norm(const Vector13& next, const Vector13& error) const {
    if (!next.allFinite() || !error.allFinite()) return NAN;
    double worst = 0.0;
    const auto against = [&](double err, double magnitude) {
      if (err > 0.0) worst = std::max(worst, err / (atol_ + rtol_ * magnitude));
    };
    for (const int start : {0, 3, 10}) {  // x, v, L
      against(error.segment<3>(start).norm(),
              std::max(y_.segment<3>(start).norm(), next.segment<3>(start).norm()));
    }
    // The angle between the orientations of next and of the 4th-order solution next - error:
    // to first order 2 |e_perp| / |q|, e_perp the part of q's error orthogonal to q (the part
    // along q changes only its length, which the renormalisation removes). From the error
    // itself, not from the difference of two orientations, whose rounding (1e-16 rad) would
    // be a floor no step size could get under.
    const Eigen::Vector4d q = next.segment<4>(6), e = error.segment<4>(6);
    const double length = q.norm();
    const Eigen::Vector4d e_perp = e - (e.dot(q) / (length * length)) * q;
    against(2.0 * e_perp.norm() / length, 1.0);
    return worst;
  }

  /// 2 E = L_b . J^-1 L_b, L_b = R^T L: the rotational kinetic energy (times 2) at y.
  double rotational_energy(const Vector13& y) const {
    const Eigen::Vector3d body_momentum =
        quaternion_of(y).normalized().conjugate() * y.segment<3>(10);
    return body_momentum.dot(body_momentum.cwiseQuotient(body_.moments));
  }

  /// For a torque-free body (world L constant, so only q moves the energy): turns q by the
  /// world rotation theta that one Newton step gives for 2E(q) = 2E0. Turning q by theta
  /// changes 2E by 2 theta . (w x L), so theta = -(2E - 2E0) g / |g|^2 with g = 2 w x L.
  /// Skipped when the correction would exceed the orientation's error scale, atol + rtol: the
  /// energy is then nearly stationary in q (a spin close to a principal axis), where its
  /// errors are of second order and the gradient too small to correct them. True when q moved.
  bool restore_energy() {
    const Eigen::Quaterniond q = quaternion_of(y_);
    const Eigen::Vector3d momentum = y_.segment<3>(10);
    const Eigen::Vector3d omega = q * (q.conjugate() * momentum).cwiseQuotient(body_.moments);
    const Eigen::Vector3d gradient = 2.0 * omega.cross(momentum);
    const double excess = rotational_energy(y_) - energy_;
    if (excess == 0.0) return false;
    const Eigen::Vector3d theta = (-excess / gradient.squaredNorm()) * gradient;
    if (!(theta.norm() <= atol_ + rtol_)) return false;
    const Eigen::Quaterniond turned = (rotation_quaternion(theta) * q).normalized();
    y_.segment<4>(6) << turned.w(), turned.x(), turned.y(), turned.z();
    return true;
  }

  /// Dormand and Prince's continuous extension of the accepted step (Hairer, Norsett, Wanner
  /// 1993, II.6; Shampine 1986): a 4th-order polynomial through y_n and y_n+1 with the slopes
  /// k1 and k7 at its ends, in the nested form y(theta) = r1 + theta (r2 + (1 - theta) (r3 +
  /// theta (r4 + (1 - theta) r5))).
  void keep_interpolant(double h, const Stages& k, const Vector13& next) {
    constexpr double d1 = -12715105075.0 / 11282082432.0, d3 = 87487479700.0 / 32700410799.0,
                     d4 = -10690763975.0 / 1880347072.0, d5 = 701980252875.0 / 199316789632.0,
                     d6 = -1453857185.0 / 822651844.0, d7 = 69997945.0 / 29380423.0;
    dense_[0] = y_;
    dense_[1] = next - y_;
    dense_[2] = h * k[0] - dense_[1];
    dense_[3] = dense_[1] - h * k[6] - dense_[2];
    dense_[4] = h * (d1 * k[0] + d3 * k[2] + d4 * k[3] + d5 * k[4] + d6 * k[5] + d7 * k[6]);
    interval_start_ = t_;
    interval_length_ = h;
  }

  /// The state at `time` in the last accepted step, q renormalised.
  Vector13 interpolate(double time) const {
    const double theta = (time - interval_start_) / interval_length_, rest = 1.0 - theta;
    Vector13 y = dense_[0] +
                 theta * (dense_[1] + rest * (dense_[2] + theta * (dense_[3] + rest * dense_[4])));
    const Eigen::Quaterniond q = quaternion_of(y).normalized();
    y.segment<4>(6) << q.w(), q.x(), q.y(), q.z();
    return y;
  }

  Vector13 rate(const Vector13& y) const {
    ++evaluations_;
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

  /// Dormand-Prince 5(4) tableau from k[0] = f(y): fills k[1..6] (k[6] = f(next), first same
  /// as last), the 5th-order `next` and the embedded error estimate.
  void attempt(const Vector13& y, double h, Stages& k, Vector13& next, Vector13& error) const {
    k[1] = rate(y + h * (1.0 / 5.0) * k[0]);
    k[2] = rate(y + h * ((3.0 / 40.0) * k[0] + (9.0 / 40.0) * k[1]));
    k[3] = rate(y + h * ((44.0 / 45.0) * k[0] - (56.0 / 15.0) * k[1] + (32.0 / 9.0) * k[2]));
    k[4] = rate(y + h * ((19372.0 / 6561.0) * k[0] - (25360.0 / 2187.0) * k[1] +
                         (64448.0 / 6561.0) * k[2] - (212.0 / 729.0) * k[3]));
    k[5] =
        rate(y + h * ((9017.0 / 3168.0) * k[0] - (355.0 / 33.0) * k[1] + (46732.0 / 5247.0) * k[2] +
                      (49.0 / 176.0) * k[3] - (5103.0 / 18656.0) * k[4]));
    next = y + h * ((35.0 / 384.0) * k[0] + (500.0 / 1113.0) * k[2] + (125.0 / 192.0) * k[3] -
                    (2187.0 / 6784.0) * k[4] + (11.0 / 84.0) * k[5]);
    k[6] = rate(next);
    error = h * ((71.0 / 57600.0) * k[0] - (71.0 / 16695.0) * k[2] + (71.0 / 1920.0) * k[3] -
                 (17253.0 / 339200.0) * k[4] + (22.0 / 525.0) * k[5] - (1.0 / 40.0) * k[6]);
  }

  const BodyModel& body_;
  double rtol_;
  double atol_;
  bool keeps_energy_;    ///< torque-free: the rotational energy is projected back after each step
  double energy_ = 0.0;  ///< 2 E at the last restart (torque-free bodies)
  double step_ = 0.0;    ///< the controller's current step, kept across output steps
  // The integration proper, possibly ahead of the output time: (t_, y_) and f(y_).
  bool started_ = false;
  double t_ = 0.0;
  Vector13 y_ = Vector13::Zero();
  Vector13 k1_ = Vector13::Zero();
  // The last accepted step, [interval_start_, interval_start_ + interval_length_].
  std::array<Vector13, 5> dense_{};
  double interval_start_ = 0.0;
  double interval_length_ = 0.0;
  // What the last call handed back, and when.
  BodyState handed_;
  double handed_time_ = 0.0;
  std::size_t accepted_ = 0, rejected_ = 0;
  mutable std::size_t evaluations_ = 0;
};

}  // namespace

std::unique_ptr<BodyStepper> make_rk4(const BodyModel& body) {
  return std::make_unique<Rk4>(body);
}
std::unique_ptr<BodyStepper> make_dopri(const BodyModel& body, const StepSettings& settings) {
  return std::make_unique<Dopri>(body, settings);
}

}  // namespace tumble::engine::steppers
