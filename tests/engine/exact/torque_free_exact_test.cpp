// The exact torque-free solution against an independent oracle: classical RK4 on
// (q, omega_body) in long double with a small step (Euler's equations and dq/dt = q (0, w) / 2),
// plus conservation laws, closed forms for symmetric bodies and the group property of the flow.
#include "engine/exact/torque_free_exact.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace tumble::engine {
namespace {

using Regime = TorqueFreeMotion::Regime;
using LD = long double;

// Orientation error: geodesic angle between two unit quaternions (engine/PHYSICS.md §5).
double angle_between(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  const Eigen::Quaterniond r = a.conjugate() * b;
  return 2.0 * std::atan2(r.vec().norm(), std::abs(r.w()));
}

double relative(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return (a - b).norm() / b.norm();
}

// Independent reference: RK4 in long double.
struct Rk4 {
  std::array<LD, 3> moments;
  std::array<LD, 4> q;  // w, x, y, z
  std::array<LD, 3> w;
  LD t = 0.0L;

  Rk4(const Eigen::Vector3d& i, const Eigen::Quaterniond& q0, const Eigen::Vector3d& w0)
      : moments{i.x(), i.y(), i.z()}, q{q0.w(), q0.x(), q0.y(), q0.z()}, w{w0.x(), w0.y(), w0.z()} {
    const LD norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    for (LD& c : q) c /= norm;
  }

  using Vec7 = std::array<LD, 7>;
  Vec7 derivative(const Vec7& s) const {
    const LD* p = s.data();
    const LD* o = s.data() + 4;
    const LD i1 = moments[0], i2 = moments[1], i3 = moments[2];
    return {-0.5L * (p[1] * o[0] + p[2] * o[1] + p[3] * o[2]),
            0.5L * (p[0] * o[0] + p[2] * o[2] - p[3] * o[1]),
            0.5L * (p[0] * o[1] + p[3] * o[0] - p[1] * o[2]),
            0.5L * (p[0] * o[2] + p[1] * o[1] - p[2] * o[0]),
            (i2 - i3) * o[1] * o[2] / i1,
            (i3 - i1) * o[2] * o[0] / i2,
            (i1 - i2) * o[0] * o[1] / i3};
  }
  Vec7 pack() const { return {q[0], q[1], q[2], q[3], w[0], w[1], w[2]}; }
  void step(LD h) {
    const Vec7 s = pack();
    auto add = [](const Vec7& a, LD c, const Vec7& b) {
      Vec7 r;
      for (int i = 0; i < 7; ++i) r[i] = a[i] + c * b[i];
      return r;
    };
    const Vec7 k1 = derivative(s);
    const Vec7 k2 = derivative(add(s, h / 2, k1));
    const Vec7 k3 = derivative(add(s, h / 2, k2));
    const Vec7 k4 = derivative(add(s, h, k3));
    Vec7 r;
    for (int i = 0; i < 7; ++i) r[i] = s[i] + h / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
    for (int i = 0; i < 4; ++i) q[i] = r[i];
    for (int i = 0; i < 3; ++i) w[i] = r[i + 4];
    t += h;
  }
  Eigen::Quaterniond orientation() const {
    return Eigen::Quaterniond(static_cast<double>(q[0]), static_cast<double>(q[1]),
                              static_cast<double>(q[2]), static_cast<double>(q[3]))
        .normalized();
  }
  Eigen::Vector3d omega() const {
    return {static_cast<double>(w[0]), static_cast<double>(w[1]), static_cast<double>(w[2])};
  }
};

struct Errors {
  double angle = 0.0;
  double omega = 0.0;
};

// Steps RK4 to t_end with step h, comparing with the exact motion every `every` steps.
Errors compare_with_rk4(const Eigen::Vector3d& moments, const Eigen::Quaterniond& q0,
                        const Eigen::Vector3d& w0, double t_end, double h, int every = 500) {
  const TorqueFreeMotion exact(moments, q0, w0);
  Rk4 ref(moments, q0, w0);
  const long steps = std::lround(t_end / std::abs(h));
  Errors e;
  for (long i = 1; i <= steps; ++i) {
    ref.step(h);
    if (i % every == 0 || i == steps) {
      const TorqueFreeMotion::State s = exact.at(static_cast<double>(i) * h);
      e.angle = std::max(e.angle, angle_between(ref.orientation(), s.orientation));
      e.omega = std::max(e.omega, relative(s.omega_body, ref.omega()));
    }
  }
  return e;
}

const Eigen::Quaterniond kQ0(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
const Eigen::Vector3d kTHandle(1.0, 2.0, 3.0);

TEST(TorqueFreeMotion, THandleFlipsMatchRk4OverTenFlips) {
  const Eigen::Vector3d w0(0.05, 1.0, 0.03);
  const TorqueFreeMotion motion(kTHandle, kQ0, w0);
  ASSERT_EQ(motion.regime(), Regime::kAboutLargestAxis);
  const double t_end = 10.0 * motion.flip_interval();
  const Errors e = compare_with_rk4(kTHandle, kQ0, w0, t_end, 1e-3);
  EXPECT_LT(e.angle, 1e-10);
  EXPECT_LT(e.omega, 1e-10);
  // The oracle itself has converged: halving its step changes nothing at this level.
  const Errors coarse = compare_with_rk4(kTHandle, kQ0, w0, t_end, 2e-3, 250);
  EXPECT_LT(coarse.angle, 1e-10);
}

TEST(TorqueFreeMotion, GenericCasesAndBothRegimesMatchRk4) {
  struct Case {
    Eigen::Vector3d moments;
    Eigen::Vector3d omega;
    Regime regime;
  };
  const std::vector<Case> cases = {
      {{1, 2, 3}, {0.3, 0.2, 1.0}, Regime::kAboutLargestAxis},
      {{1, 2, 3}, {1.0, 0.2, 0.3}, Regime::kAboutSmallestAxis},
      {{1, 2, 3}, {-1.0, -0.4, -0.3}, Regime::kAboutSmallestAxis},
      {{2, 3, 1}, {-1.0, 0.2, -0.3}, Regime::kAboutLargestAxis},
      {{0.3, 0.5, 0.7}, {4.0, -3.0, 2.0}, Regime::kAboutSmallestAxis},
      {{1, 10, 10.5}, {0.001, 0.3, 1.0}, Regime::kAboutLargestAxis},   // large |n|
      {{1, 1 + 1e-9, 3}, {0.5, 0.2, 1.0}, Regime::kAboutLargestAxis},  // nearly symmetric
      {{1, 2, 3}, {1e-6, 1.0, 1e-6}, Regime::kAboutLargestAxis},       // m1 ~ 1e-12
  };
  for (const Case& c : cases) {
    const TorqueFreeMotion motion(c.moments, kQ0, c.omega);
    EXPECT_EQ(motion.regime(), c.regime) << c.moments.transpose() << " | " << c.omega.transpose();
    const Errors e = compare_with_rk4(c.moments, kQ0, c.omega, 40.0, 5e-4);
    EXPECT_LT(e.angle, 1e-10) << c.moments.transpose() << " | " << c.omega.transpose();
    EXPECT_LT(e.omega, 1e-10) << c.moments.transpose() << " | " << c.omega.transpose();
  }
}

TEST(TorqueFreeMotion, NegativeTimesMatchBackwardRk4) {
  const Errors e = compare_with_rk4(kTHandle, kQ0, {0.4, 0.9, -0.2}, 30.0, -1e-3);
  EXPECT_LT(e.angle, 1e-10);
  EXPECT_LT(e.omega, 1e-10);
}

TEST(TorqueFreeMotion, InitialStateIsReproduced) {
  for (const Eigen::Vector3d& w0 : {Eigen::Vector3d(0.05, 1.0, 0.03), Eigen::Vector3d(1, 0.2, 0.3),
                                    Eigen::Vector3d(-0.3, -0.2, -1.0)}) {
    const TorqueFreeMotion motion(kTHandle, kQ0, w0);
    const TorqueFreeMotion::State s = motion.at(0.0);
    EXPECT_LT(angle_between(s.orientation, kQ0), 1e-15);
    EXPECT_LT(relative(s.omega_body, w0), 1e-15);
  }
}

TEST(TorqueFreeMotion, InvariantsHoldOverLongTimes) {
  const Eigen::Vector3d w0(0.4, 0.9, -0.2);
  const TorqueFreeMotion motion(kTHandle, kQ0, w0);
  const Eigen::Vector3d l0 = motion.angular_momentum_world();
  for (double t : {0.1, 3.0, 1e2, 1e3, 1e4, 1e5, -1e5}) {
    const TorqueFreeMotion::State s = motion.at(t);
    const Eigen::Vector3d lb = kTHandle.cwiseProduct(s.omega_body);
    EXPECT_NEAR(0.5 * s.omega_body.dot(lb) / motion.energy(), 1.0, 2e-15) << t;
    EXPECT_LT(relative(s.orientation * lb, l0), 2e-14) << t;
    EXPECT_NEAR(s.orientation.norm(), 1.0, 2e-16);
  }
}

TEST(TorqueFreeMotion, LongTimesAreConsistentWithRestartingTheFlow) {
  // phi(t) = n Phi_period + phi(t mod period): the flow restarted from the state after
  // hundreds of periods continues exactly as the original flow.
  const Eigen::Vector3d w0(0.3, 0.2, 1.0);
  const TorqueFreeMotion motion(kTHandle, kQ0, w0);
  const double period = motion.omega_period();
  for (double t1 : {317.3 * period, 999.9 * period}) {
    const TorqueFreeMotion::State s1 = motion.at(t1);
    const TorqueFreeMotion restarted(kTHandle, s1.orientation, s1.omega_body);
    for (double t2 : {0.37, 0.5 * period, 3.3 * period}) {
      const TorqueFreeMotion::State a = motion.at(t1 + t2);
      const TorqueFreeMotion::State b = restarted.at(t2);
      EXPECT_LT(angle_between(a.orientation, b.orientation), 1e-11) << t1 << " " << t2;
      EXPECT_LT(relative(a.omega_body, b.omega_body), 1e-11) << t1 << " " << t2;
    }
  }
  // Over a full period omega returns; the orientation turns about L by precession_per_period.
  const TorqueFreeMotion::State end = motion.at(period);
  EXPECT_LT(relative(end.omega_body, w0), 1e-14);
  const Eigen::Vector3d axis = motion.angular_momentum_world().normalized();
  const Eigen::Quaterniond turned =
      Eigen::Quaterniond(Eigen::AngleAxisd(motion.precession_per_period(), axis)) * kQ0;
  EXPECT_LT(angle_between(end.orientation, turned), 1e-13);
}

TEST(TorqueFreeMotion, OrientationIsContinuousInTime) {
  const TorqueFreeMotion motion(kTHandle, kQ0, {0.05, 1.0, 0.03});
  const double h = 1e-3;
  Eigen::Quaterniond previous = motion.at(0.0).orientation;
  for (int i = 1; i <= 60000; ++i) {
    const Eigen::Quaterniond q = motion.at(i * h).orientation;
    // Continuous as a quaternion (no sign flips), not only as a rotation.
    ASSERT_LT((q.coeffs() - previous.coeffs()).norm(), 2e-3) << i * h;
    previous = q;
  }
}

TEST(TorqueFreeMotion, FlipIntervalMatchesSignChangesOfTheIntermediateComponent) {
  const Eigen::Vector3d w0(0.05, 1.0, 0.03);
  const TorqueFreeMotion motion(kTHandle, kQ0, w0);
  Rk4 ref(kTHandle, kQ0, w0);
  const LD h = 1e-3L;
  std::vector<double> crossings;
  LD w2_prev = ref.w[1];
  LD dw2_prev = ref.derivative(ref.pack())[5];
  while (ref.t < 6.0L * motion.flip_interval()) {
    ref.step(h);
    const LD w2 = ref.w[1];
    const LD dw2 = ref.derivative(ref.pack())[5];
    if ((w2 < 0) != (w2_prev < 0)) {
      // Root of the cubic Hermite interpolant on the step, by Newton from the secant guess.
      LD s = w2_prev / (w2_prev - w2);
      for (int it = 0; it < 20; ++it) {
        const LD h00 = 2 * s * s * s - 3 * s * s + 1, h10 = s * s * s - 2 * s * s + s;
        const LD h01 = -2 * s * s * s + 3 * s * s, h11 = s * s * s - s * s;
        const LD p = h00 * w2_prev + h10 * h * dw2_prev + h01 * w2 + h11 * h * dw2;
        const LD dp = (6 * s * s - 6 * s) * w2_prev + (3 * s * s - 4 * s + 1) * h * dw2_prev +
                      (-6 * s * s + 6 * s) * w2 + (3 * s * s - 2 * s) * h * dw2;
        s -= p / dp;
      }
      crossings.push_back(static_cast<double>(ref.t - h + s * h));
    }
    w2_prev = w2;
    dw2_prev = dw2;
  }
  ASSERT_GE(crossings.size(), 5u);
  for (std::size_t i = 1; i < crossings.size(); ++i) {
    EXPECT_NEAR(crossings[i] - crossings[i - 1], motion.flip_interval(), 1e-9);
  }
  EXPECT_NEAR(motion.omega_period(), 2.0 * motion.flip_interval(), 1e-12);
}

TEST(TorqueFreeMotion, SymmetricBodyPrecessesRegularly) {
  const Eigen::Vector3d moments(1.0, 1.0, 3.0);
  const Eigen::Vector3d w0(0.5, 0.2, 1.0);
  const TorqueFreeMotion motion(moments, kQ0, w0);
  EXPECT_EQ(motion.parameter(), 0.0);
  EXPECT_TRUE(std::isinf(motion.flip_interval()));
  const double rate = (moments.z() - moments.x()) / moments.x() * w0.z();
  const double g = moments.cwiseProduct(w0).norm();
  const Eigen::Vector3d l_hat = motion.angular_momentum_world().normalized();
  const Eigen::Vector3d axis0 = kQ0 * Eigen::Vector3d::UnitZ();
  EXPECT_NEAR(motion.omega_period(), 2.0 * std::numbers::pi / rate, 1e-14);
  for (double t : {0.3, 2.0, 17.0, 1234.5}) {
    const TorqueFreeMotion::State s = motion.at(t);
    // Body omega turns about the symmetry axis at (I3 - I1)/I1 w3.
    const Eigen::Vector3d expected_w = Eigen::AngleAxisd(rate * t, Eigen::Vector3d::UnitZ()) * w0;
    EXPECT_LT(relative(s.omega_body, expected_w), 1e-15 * (10.0 + rate * t)) << t;
    // The symmetry axis cones about L at G / I1.
    const Eigen::Vector3d expected_axis = Eigen::AngleAxisd(g / moments.x() * t, l_hat) * axis0;
    EXPECT_LT((s.orientation * Eigen::Vector3d::UnitZ() - expected_axis).norm(), 1e-12) << t;
  }
  // The prolate case I1 < I2 = I3 circles the smallest axis.
  const Eigen::Vector3d prolate(1.0, 3.0, 3.0);
  const TorqueFreeMotion rod(prolate, kQ0, {1.0, 0.2, 0.5});
  EXPECT_EQ(rod.regime(), Regime::kAboutSmallestAxis);
  const Errors e = compare_with_rk4(prolate, kQ0, {1.0, 0.2, 0.5}, 30.0, 5e-4);
  EXPECT_LT(e.angle, 1e-10);
  EXPECT_LT(e.omega, 1e-10);
}

TEST(TorqueFreeMotion, SeparatrixIsFiniteAndMatchesRk4) {
  // I = (3, 4, 6), w = (2, w2, 1): G^2 - 2T I2 = 3(3-4) 4 + 6(6-4) 1 = 0 exactly.
  const Eigen::Vector3d moments(3.0, 4.0, 6.0);
  const Eigen::Vector3d w0(2.0, 0.5, 1.0);
  const TorqueFreeMotion motion(moments, kQ0, w0);
  ASSERT_EQ(motion.regime(), Regime::kSeparatrix);
  EXPECT_TRUE(std::isinf(motion.omega_period()));
  EXPECT_TRUE(std::isinf(motion.flip_interval()));
  const Errors e = compare_with_rk4(moments, kQ0, w0, 15.0, 5e-4);
  EXPECT_LT(e.angle, 1e-10);
  EXPECT_LT(e.omega, 1e-10);
  // Far in the future the body spins about the intermediate axis; nothing is NaN.
  for (double t : {1e3, 1e6, -1e6}) {
    const TorqueFreeMotion::State s = motion.at(t);
    EXPECT_TRUE(s.orientation.coeffs().allFinite());
    EXPECT_TRUE(s.omega_body.allFinite());
    EXPECT_NEAR(std::abs(s.omega_body.y()), std::sqrt(2.0 * motion.energy() / moments.y()), 1e-12);
  }
  // Slightly off the separatrix on either side: finite and consistent with RK4.
  for (double eps : {1e-9, -1e-9}) {
    const Eigen::Vector3d w(2.0, 0.5, 1.0 + eps);
    const TorqueFreeMotion near(moments, kQ0, w);
    EXPECT_EQ(near.regime(), eps > 0 ? Regime::kAboutLargestAxis : Regime::kAboutSmallestAxis);
    EXPECT_TRUE(std::isfinite(near.flip_interval()));
    const Errors en = compare_with_rk4(moments, kQ0, w, 15.0, 5e-4);
    EXPECT_LT(en.angle, 1e-10) << eps;
    EXPECT_LT(en.omega, 1e-10) << eps;
  }
}

TEST(TorqueFreeMotion, AllOrderingsOfTheMomentsGiveTheSameMotion) {
  const Eigen::Vector3d w0(0.4, 0.9, -0.2);
  const TorqueFreeMotion base(kTHandle, kQ0, w0);
  const std::array<std::array<int, 3>, 6> perms = {
      {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
  for (const auto& perm : perms) {
    // New body axes are a proper signed permutation Q of the old: v_new = Q v_old.
    Eigen::Matrix3d q = Eigen::Matrix3d::Zero();
    for (int k = 0; k < 3; ++k) q(k, perm[k]) = 1.0;
    if (q.determinant() < 0) q.row(2) *= -1.0;
    const Eigen::Vector3d moments(kTHandle[perm[0]], kTHandle[perm[1]], kTHandle[perm[2]]);
    const Eigen::Quaterniond qq(q);
    const TorqueFreeMotion other(moments, kQ0 * qq.conjugate(), q * w0);
    for (double t : {0.0, 1.7, 25.0, 400.0}) {
      const TorqueFreeMotion::State a = base.at(t);
      const TorqueFreeMotion::State b = other.at(t);
      EXPECT_LT(angle_between(a.orientation * qq.conjugate(), b.orientation), 1e-12) << t;
      EXPECT_LT(relative(b.omega_body, q * a.omega_body), 1e-12) << t;
    }
  }
}

TEST(TorqueFreeMotion, TrivialMotions) {
  // At rest.
  const TorqueFreeMotion rest(kTHandle, kQ0, Eigen::Vector3d::Zero());
  EXPECT_EQ(rest.regime(), Regime::kAtRest);
  EXPECT_LT(angle_between(rest.at(5.0).orientation, kQ0), 1e-16);
  EXPECT_EQ(rest.at(5.0).omega_body, Eigen::Vector3d::Zero());
  // Spin about each principal axis (including the unstable one) and any axis of a sphere:
  // q(t) = q0 exp(t w / 2).
  const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> spins = {
      {kTHandle, {0, 0, 2}},
      {kTHandle, {0, -1.5, 0}},
      {kTHandle, {3, 0, 0}},
      {{2, 2, 2}, {0.3, -0.4, 1.2}},
      {{1, 2, 2}, {0, 0.6, 0.8}}};
  for (const auto& [moments, w] : spins) {
    const TorqueFreeMotion spin(moments, kQ0, w);
    EXPECT_EQ(spin.regime(), Regime::kPermanentRotation) << moments.transpose();
    for (double t : {0.5, 100.0}) {
      const Eigen::Quaterniond expected = kQ0 * Eigen::AngleAxisd(w.norm() * t, w.normalized());
      EXPECT_LT(angle_between(spin.at(t).orientation, expected), 1e-13);
      EXPECT_EQ(spin.at(t).omega_body, w);
    }
  }
  // A spin a hair off the largest axis nutates by that hair.
  const TorqueFreeMotion wobble(kTHandle, kQ0, {1e-9, 0.0, 1.0});
  EXPECT_EQ(wobble.regime(), Regime::kAboutLargestAxis);
  const Eigen::Quaterniond spin_only = kQ0 * Eigen::AngleAxisd(10.0, Eigen::Vector3d::UnitZ());
  EXPECT_LT(angle_between(wobble.at(10.0).orientation, spin_only), 1e-8);
}

TEST(TorqueFreeMotion, ExtremeScalesAreHandled) {
  // The motion is homogeneous: scaling omega scales time, scaling moments changes nothing.
  const Eigen::Vector3d w0(0.4, 0.9, -0.2);
  const TorqueFreeMotion base(kTHandle, kQ0, w0);
  const TorqueFreeMotion fast(1e-150 * kTHandle, kQ0, 1e150 * w0);
  const TorqueFreeMotion slow(1e150 * kTHandle, kQ0, 1e-150 * w0);
  for (double t : {0.7, 30.0}) {
    const TorqueFreeMotion::State a = base.at(t);
    EXPECT_LT(angle_between(fast.at(t * 1e-150).orientation, a.orientation), 1e-13);
    EXPECT_LT(angle_between(slow.at(t * 1e150).orientation, a.orientation), 1e-13);
    EXPECT_LT(relative(1e-150 * fast.at(t * 1e-150).omega_body, a.omega_body), 1e-13);
  }
}

TEST(TorqueFreeMotion, BadInput) {
  EXPECT_THAT(
      [] {
        TorqueFreeMotion m({1.0, -2.0, 3.0}, kQ0, {1, 0, 0});
      },
      ::testing::ThrowsMessage<std::invalid_argument>(::testing::HasSubstr("finite and positive")));
  EXPECT_THROW(TorqueFreeMotion({1.0, std::nan(""), 3.0}, kQ0, {1, 0, 0}), std::invalid_argument);
  // A non-finite state does not throw (step loops detect NaN instead).
  const TorqueFreeMotion nan(kTHandle, kQ0, {std::nan(""), 1.0, 0.0});
  EXPECT_EQ(nan.regime(), Regime::kInvalid);
  EXPECT_FALSE(nan.at(1.0).omega_body.allFinite());
  EXPECT_FALSE(nan.at(1.0).orientation.coeffs().allFinite());
}

}  // namespace
}  // namespace tumble::engine
