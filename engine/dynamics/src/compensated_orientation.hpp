#pragma once
// Private to the engine: an orientation updated by compensated summation.
//
// A step turns the orientation by a small rotation, q <- (1 + delta) q with |delta| ~ h |w| / 2.
// Rounding the product to doubles costs an error of ~1e-16 absolute in q every step, whatever
// h is, so over a fixed duration the error grows with the number of steps. Through q^T L it
// also kicks the energy by ~1e-16 relative every step; near the separatrix of an intermediate
// axis spin that random walk of the energy moves the flip times: once truncation was below
// rounding, the orientation error grew as the step shrank (engine/PHYSICS.md §3, Rounding).
// Kept as an unevaluated sum hi + lo (Kahan 1965; Moller 1965), q is instead updated as
// q + delta q, whose rounding is relative to the increment delta q, not to q: the error per
// step falls with h, as truncation does. The low part lives in the stepper, so it is reused
// only while the state it is handed is the one it returned (compared bit for bit); anything
// else (another stepper's state, a state edited between steps) starts over with lo = 0.
#include <cmath>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "engine/body/rigid_body.hpp"

namespace tumble::engine::steppers {

/// The small part delta = exp(theta / 2) - 1 of a turn by the rotation vector theta, to
/// rounding relative to delta (w = cos - 1 from HalfAngle, not cos rounded near 1).
inline Eigen::Quaterniond small_turn(const Eigen::Vector3d& theta) {
  const HalfAngle f = half_angle(0.25 * theta.squaredNorm());
  const Eigen::Vector3d v = (0.5 * f.sinc) * theta;
  return {f.cos_minus_one, v.x(), v.y(), v.z()};
}

/// The small part of (1 + a)(1 + b): a + b + a b, as accurate as a and b themselves.
inline Eigen::Quaterniond compose_small(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return Eigen::Quaterniond((a.coeffs() + b.coeffs()) + (a * b).coeffs());
}

class CompensatedOrientation {
 public:
  /// Starts a step from `q`: keeps the low part when `q` is what value() last returned;
  /// otherwise starts from `q` alone, scaled to unit length (hi + lo unit far below rounding).
  void resume(const Eigen::Quaterniond& q) {
    if (q.coeffs() == hi_) return;
    hi_ = q.coeffs();
    lo_.setZero();
    double excess = norm_squared_excess(hi_);
    if (!(std::abs(excess) < 1e-8)) {  // not unit to rounding: normalise plainly first
      hi_.normalize();
      excess = norm_squared_excess(hi_);
    }
    add(-0.5 * excess * hi_);  // 1 / sqrt(1 + e) = 1 - e / 2 to rounding for |e| < 1e-8
  }
  /// q <- (1 + delta) q: a turn in world axes by the small part delta (small_turn).
  void turn_world(const Eigen::Quaterniond& delta) { add((unit(delta) * value()).coeffs()); }
  /// q <- q (1 + delta): a turn in body axes.
  void turn_body(const Eigen::Quaterniond& delta) { add((value() * unit(delta)).coeffs()); }
  /// The orientation rounded to doubles (what BodyState holds).
  Eigen::Quaterniond value() const { return Eigen::Quaterniond(hi_); }

 private:
  using Coefficients = Eigen::Vector4d;  // x, y, z, w (Eigen's storage order)

  /// delta scaled so that |1 + delta| = 1 to second order in the rounding of delta: e =
  /// |1 + delta|^2 - 1 = 2 delta_w + |delta|^2 is a sum of small terms, so exact to its own
  /// rounding, and (1 + delta)(1 - e / 2) is the unit turn. |q| then drifts by no more than the
  /// rounding of each increment, not by that of q.
  static Eigen::Quaterniond unit(const Eigen::Quaterniond& delta) {
    const double excess = 2.0 * delta.w() + delta.coeffs().squaredNorm();
    Eigen::Quaterniond out(delta.coeffs() * (1.0 - 0.5 * excess));
    out.w() -= 0.5 * excess;
    return out;
  }
  /// |q|^2 - 1 without cancellation: each square split exactly by fma, the additions'
  /// rounding errors kept (Ogita, Rump, Oishi 2005, "Accurate sum and dot product").
  static double norm_squared_excess(const Coefficients& q) {
    double sum = -1.0;
    double tail = 0.0;
    for (int i = 0; i < 4; ++i) {
      const double square = q[i] * q[i];
      const double next = sum + square;
      tail += two_sum_error(sum, square, next) + std::fma(q[i], q[i], -square);
      sum = next;
    }
    return sum + tail;
  }
  /// The rounding error of sum = a + b (Knuth's TwoSum: exact, for any magnitudes).
  static double two_sum_error(double a, double b, double sum) {
    const double b_part = sum - a;
    return (a - (sum - b_part)) + (b - b_part);
  }
  /// hi + lo <- hi + lo + increment, with hi the rounded sum and lo what rounding left out. The
  /// increment is formed from hi alone: lo delta is below the rounding of the increment.
  void add(const Coefficients& increment) {
    for (int i = 0; i < 4; ++i) {
      const double small = lo_[i] + increment[i];
      const double sum = hi_[i] + small;
      lo_[i] = two_sum_error(hi_[i], small, sum);
      hi_[i] = sum;
    }
  }

  Coefficients hi_ = Eigen::Quaterniond::Identity().coeffs();
  Coefficients lo_ = Coefficients::Zero();
};

}  // namespace tumble::engine::steppers
