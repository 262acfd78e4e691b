// Principal moments and axes: ascending, proper, reconstructing; the rigid-body moment checks.
#include "engine/mass/principal_frame.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <random>

namespace tumble::engine {
namespace {

using ::testing::HasSubstr;

Eigen::Matrix3d random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  const Eigen::Quaterniond q(normal(rng), normal(rng), normal(rng), normal(rng));
  return q.normalized().toRotationMatrix();
}

/// Checks the frame's contract for `inertia` whose exact moments (ascending) are `expected`.
void expect_valid_frame(const Eigen::Matrix3d& inertia, const Eigen::Vector3d& expected) {
  const PrincipalFrame frame = principal_frame(inertia);
  const double scale = expected.cwiseAbs().maxCoeff();

  // Moments ascending and equal to the ones the tensor was built from.
  EXPECT_LE(frame.moments[0], frame.moments[1]);
  EXPECT_LE(frame.moments[1], frame.moments[2]);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(frame.moments[i], expected[i], 1e-14 * scale) << i;

  // A proper rotation: orthonormal columns, determinant +1.
  const Eigen::Matrix3d gram = frame.axes.transpose() * frame.axes;
  EXPECT_LT((gram - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_NEAR(frame.axes.determinant(), 1.0, 1e-14);

  // inertia = axes diag(moments) axes^T.
  const Eigen::Matrix3d rebuilt = frame.axes * frame.moments.asDiagonal() * frame.axes.transpose();
  EXPECT_LT((rebuilt - inertia).cwiseAbs().maxCoeff(), 1e-14 * scale) << "inertia\n"
                                                                      << inertia << "\nrebuilt\n"
                                                                      << rebuilt;

  // Each axis is an eigenvector of its own moment.
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d residual =
        inertia * frame.axes.col(i) - frame.moments[i] * frame.axes.col(i);
    EXPECT_LT(residual.norm(), 1e-14 * scale) << "axis " << i;
  }
}

TEST(PrincipalFrame, DiagonalTensorKeepsCoordinateAxes) {
  const Eigen::Matrix3d inertia = Eigen::Vector3d(3.0, 1.0, 2.0).asDiagonal();
  const PrincipalFrame frame = principal_frame(inertia);
  EXPECT_EQ(frame.moments, Eigen::Vector3d(1.0, 2.0, 3.0));
  // Ascending moments 1, 2, 3 belong to y, z, x; signs canonical (largest component positive).
  EXPECT_TRUE(frame.axes.col(0).isApprox(Eigen::Vector3d::UnitY(), 1e-15));
  EXPECT_TRUE(frame.axes.col(1).isApprox(Eigen::Vector3d::UnitZ(), 1e-15));
  EXPECT_TRUE(frame.axes.col(2).isApprox(Eigen::Vector3d::UnitX(), 1e-15));
  expect_valid_frame(inertia, Eigen::Vector3d(1.0, 2.0, 3.0));
}

TEST(PrincipalFrame, RandomRotatedDiagonalTensors) {
  std::mt19937_64 rng(20240611);
  std::uniform_real_distribution<double> moment(0.1, 10.0);
  for (int trial = 0; trial < 200; ++trial) {
    Eigen::Vector3d moments(moment(rng), moment(rng), moment(rng));
    std::sort(moments.data(), moments.data() + 3);
    const Eigen::Matrix3d rotation = random_rotation(rng);
    const Eigen::Matrix3d inertia = rotation * moments.asDiagonal() * rotation.transpose();
    SCOPED_TRACE(trial);
    expect_valid_frame(inertia, moments);

    // The axes span the same lines as the rotation's columns (up to sign).
    const PrincipalFrame frame = principal_frame(inertia);
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(std::abs(frame.axes.col(i).dot(rotation.col(i))), 1.0, 1e-9) << i;
    }
  }
}

TEST(PrincipalFrame, ScaleFree) {
  std::mt19937_64 rng(7);
  for (const double scale : {1e-30, 1e-8, 1e8, 1e30}) {
    const Eigen::Vector3d moments = scale * Eigen::Vector3d(0.5, 1.25, 1.5);
    const Eigen::Matrix3d rotation = random_rotation(rng);
    SCOPED_TRACE(scale);
    expect_valid_frame(rotation * moments.asDiagonal() * rotation.transpose(), moments);
  }
}

TEST(PrincipalFrame, RepeatedMoments) {
  std::mt19937_64 rng(99);
  const Eigen::Vector3d cases[] = {
      {1.0, 1.0, 2.0},          // symmetric top, pair below
      {1.0, 2.0, 2.0},          // pair above (a rod)
      {2.0, 2.0, 2.0},          // sphere: any frame is principal
      {1.0, 1.0, 1.0 + 1e-12},  // nearly isotropic
  };
  for (const Eigen::Vector3d& moments : cases) {
    for (int trial = 0; trial < 20; ++trial) {
      const Eigen::Matrix3d rotation = random_rotation(rng);
      SCOPED_TRACE(::testing::Message() << moments.transpose() << " trial " << trial);
      expect_valid_frame(rotation * moments.asDiagonal() * rotation.transpose(), moments);
    }
  }
}

TEST(PrincipalFrame, CanonicalSigns) {
  // Flipping the sign of a rotation's columns does not change the tensor, so the frame must
  // not depend on it: first two axes have a positive largest component.
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::Matrix3d rotation = random_rotation(rng);
    const Eigen::Vector3d moments(1.0, 2.0, 4.0);
    const PrincipalFrame frame =
        principal_frame(rotation * moments.asDiagonal() * rotation.transpose());
    for (int axis = 0; axis < 2; ++axis) {
      Eigen::Index largest = 0;
      frame.axes.col(axis).cwiseAbs().maxCoeff(&largest);
      EXPECT_GT(frame.axes(largest, axis), 0.0);
    }
    EXPECT_TRUE(frame.axes.col(2).isApprox(frame.axes.col(0).cross(frame.axes.col(1)), 1e-14));
  }
}

TEST(PrincipalMomentsProblem, AcceptsRigidBodies) {
  EXPECT_EQ(principal_moments_problem({1.0, 1.0, 1.0}), std::nullopt);
  EXPECT_EQ(principal_moments_problem({0.4, 0.9, 1.1}), std::nullopt);
  // Flat plate limit: I3 = I1 + I2, exactly and within rounding.
  EXPECT_EQ(principal_moments_problem({1.0, 2.0, 3.0}), std::nullopt);
  EXPECT_EQ(principal_moments_problem({1.0, 2.0, 3.0 * (1.0 + 1e-14)}), std::nullopt);
  EXPECT_EQ(principal_moments_problem({1e-20, 2e-20, 3e-20}), std::nullopt);
  // Order does not matter.
  EXPECT_EQ(principal_moments_problem({3.0, 1.0, 2.0}), std::nullopt);
}

TEST(PrincipalMomentsProblem, RejectsNonPositive) {
  const auto zero = principal_moments_problem({0.0, 1.0, 1.0});
  ASSERT_TRUE(zero.has_value());
  EXPECT_THAT(*zero, HasSubstr("must be positive"));
  const auto negative = principal_moments_problem({-1e-3, 1.0, 1.0});
  ASSERT_TRUE(negative.has_value());
  EXPECT_THAT(*negative, HasSubstr("must be positive"));
}

TEST(PrincipalMomentsProblem, RejectsNonFinite) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& moments :
       {Eigen::Vector3d(nan, 1.0, 1.0), Eigen::Vector3d(1.0, inf, 1.0),
        Eigen::Vector3d(1.0, 1.0, -inf)}) {
    const auto problem = principal_moments_problem(moments);
    ASSERT_TRUE(problem.has_value()) << moments.transpose();
    EXPECT_THAT(*problem, HasSubstr("not finite"));
  }
}

TEST(PrincipalMomentsProblem, RejectsTriangleInequalityBreach) {
  const auto problem = principal_moments_problem({1.0, 2.0, 3.0 * (1.0 + 1e-6)});
  ASSERT_TRUE(problem.has_value());
  EXPECT_THAT(*problem, HasSubstr("triangle inequality"));
  EXPECT_THAT(*problem, HasSubstr("I3"));

  const auto first = principal_moments_problem({5.0, 1.0, 1.0});
  ASSERT_TRUE(first.has_value());
  EXPECT_THAT(*first, HasSubstr("I1 exceeds"));
}

}  // namespace
}  // namespace tumble::engine
