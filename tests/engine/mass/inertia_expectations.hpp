#pragma once
// Expectations on inertia tensors and vectors shared by the mass-property tests.

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

namespace tumble::engine::testing {

/// The accuracy target of exact mass properties, relative to the largest principal moment.
inline constexpr double kExact = 1e-12;

inline double largest_moment(const Eigen::Matrix3d& inertia) {
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(inertia, Eigen::EigenvaluesOnly)
      .eigenvalues()
      .cwiseAbs()
      .maxCoeff();
}

/// Every entry of `actual` within `relative` times the largest principal moment of `expected`.
inline void expect_inertia_near(const Eigen::Matrix3d& actual, const Eigen::Matrix3d& expected,
                                double relative = kExact) {
  const double tolerance = relative * largest_moment(expected);
  EXPECT_LE((actual - expected).cwiseAbs().maxCoeff(), tolerance) << "actual\n"
                                                                  << actual << "\nexpected\n"
                                                                  << expected;
}

/// Every component of `actual` within `tolerance` of `expected`.
inline void expect_vector_near(const Eigen::Vector3d& actual, const Eigen::Vector3d& expected,
                               double tolerance) {
  EXPECT_LE((actual - expected).cwiseAbs().maxCoeff(), tolerance)
      << "actual " << actual.transpose() << "\nexpected " << expected.transpose();
}

}  // namespace tumble::engine::testing
