// Principal moments and axes.
#include "engine/mass/principal_frame.hpp"

#include <cmath>
#include <sstream>

#include <Eigen/Eigenvalues>

namespace tumble::engine {

PrincipalFrame principal_frame(const Eigen::Matrix3d& inertia) {
  // The iterative (QR) solver: the closed-form 3x3 path loses accuracy on near-equal moments.
  const Eigen::Matrix3d symmetric = 0.5 * (inertia + inertia.transpose());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(symmetric);
  PrincipalFrame frame;
  frame.moments = solver.eigenvalues();  // ascending
  frame.axes = solver.eigenvectors();

  // Canonical signs: the first two axes point along their largest component; the third
  // makes the frame right-handed.
  for (int axis = 0; axis < 2; ++axis) {
    Eigen::Index largest = 0;
    frame.axes.col(axis).cwiseAbs().maxCoeff(&largest);
    if (frame.axes(largest, axis) < 0.0) frame.axes.col(axis) *= -1.0;
  }
  frame.axes.col(2) = frame.axes.col(0).cross(frame.axes.col(1)).normalized();
  return frame;
}

std::optional<std::string> principal_moments_problem(const Eigen::Vector3d& moments) {
  std::ostringstream message;
  message.precision(9);
  if (!moments.allFinite()) {
    message << "principal moments are not finite (" << moments.transpose() << ")";
    return message.str();
  }
  if ((moments.array() <= 0.0).any()) {
    message << "principal moments must be positive, got (" << moments.transpose() << ")";
    return message.str();
  }
  // Each moment is a sum of two second moments, so no moment exceeds the sum of the others.
  const double tolerance = 1e-9 * moments.maxCoeff();
  for (int i = 0; i < 3; ++i) {
    const double others = moments.sum() - moments[i];
    if (moments[i] > others + tolerance) {
      message << "principal moments (" << moments.transpose()
              << ") break the triangle inequality: I" << i + 1 << " exceeds the sum of the others";
      return message.str();
    }
  }
  return std::nullopt;
}

}  // namespace tumble::engine
