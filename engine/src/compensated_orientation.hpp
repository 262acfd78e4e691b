#pragma once
// Private to the engine: an orientation updated by compensated summation.
//
// A step turns the orientation by a small rotation, q <- (1 + delta) q with |delta| ~ h |w| / 2.
// Rounding the product to doubles costs an error of ~1e-16 absolute in q every step, whatever
// h is, so over a fixed duration the error grows with the number of steps. Through q^T L it
// also kicks the energy by ~1e-16 relative every step; near the separatrix of an intermediate
// axis spin that random walk of the energy moves the flip times, and the orientation error grew
// tenfold per tenfold smaller step once truncation was below rounding (engine/PHYSICS.md §3).
// Kept as an unevaluated sum hi + lo (Kahan 1965; Moller 1965), q is instead updated as
// q + delta q, whose rounding is relative to the increment delta q, not to q: the error per
// step falls with h, as truncation does. The low part lives in the stepper, so it is reused
// only while the state it is handed is the one it returned (compared bit for bit); anything
// else (another stepper's state, a state edited between steps) starts over with lo = 0.
#include <cmath>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace tumble::engine::steppers {

class CompensatedOrientation {
 public:
  /// Starts a step from `q`: keeps the low part when `q` is what value() last returned.
  void resume(const Eigen::Quaterniond& q) {
    if (q.coeffs() != hi_) {
      hi_ = q.coeffs();
      lo_.setZero();
    }
  }
  /// q <- (1 + delta) q: a turn in world axes (delta = exp(theta / 2) - 1, w = cos - 1).
  void turn_world(const Eigen::Quaterniond& delta) {
    add(product(delta, hi_) + product(delta, lo_));
  }
  /// q <- q (1 + delta): a turn in body axes.
  void turn_body(const Eigen::Quaterniond& delta) {
    add(product(hi_, delta) + product(lo_, delta));
  }
  /// Scales hi + lo to unit length, with |q|^2 - 1 computed without cancellation.
  void normalize() {
    double sum = -1.0;
    double tail = 0.0;
    for (int i = 0; i < 4; ++i) {
      const double square = hi_[i] * hi_[i];
      const double square_error = std::fma(hi_[i], hi_[i], -square);  // exact
      const double next = sum + square;
      tail += two_sum_error(sum, square, next) + square_error + 2.0 * hi_[i] * lo_[i];
      sum = next;
    }
    // 1 / sqrt(1 + e) = 1 - e / 2 to rounding: e is of the order of the rounding of one step.
    add(-0.5 * (sum + tail) * hi_);
  }
  /// The orientation rounded to doubles (what BodyState holds).
  Eigen::Quaterniond value() const { return Eigen::Quaterniond(hi_); }

 private:
  using Coefficients = Eigen::Vector4d;  // x, y, z, w (Eigen's storage order)

  static Coefficients product(const Eigen::Quaterniond& a, const Coefficients& b) {
    return (a * Eigen::Quaterniond(b)).coeffs();
  }
  static Coefficients product(const Coefficients& a, const Eigen::Quaterniond& b) {
    return (Eigen::Quaterniond(a) * b).coeffs();
  }
  /// The rounding error of sum = a + b (Knuth's TwoSum: exact, for any magnitudes).
  static double two_sum_error(double a, double b, double sum) {
    const double b_part = sum - a;
    return (a - (sum - b_part)) + (b - b_part);
  }
  /// hi + lo <- hi + lo + increment, with hi the rounded sum and lo what rounding left out.
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
