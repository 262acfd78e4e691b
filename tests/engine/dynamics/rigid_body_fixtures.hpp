#pragma once
// Bodies and a stepping loop shared by the integrator tests (integrators_test.cpp,
// symplectic_euler_test.cpp, moser_veselov_test.cpp).

#include <Eigen/Geometry>

#include "engine/body/rigid_body.hpp"
#include "engine/dynamics/integrators.hpp"

namespace tumble::engine::fixtures {

/// The start orientation of the free-body tests: 0.7 rad about (1, 2, 3).
inline const Eigen::Quaterniond kOrientation(
    Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));

/// A free body of 1 kg with principal `moments` and no force terms.
inline BodyModel free_body(const Eigen::Vector3d& moments) {
  BodyModel body;
  body.name = "free";
  body.mass = 1.0;
  body.moments = moments;
  return body;
}

/// A 1 kg top pivoted 0.5 m below its centre of mass on its third axis, under gravity.
inline BodyModel heavy_top(const Eigen::Vector3d& moments) {
  BodyModel top = free_body(moments);
  top.name = "top";
  top.pivoted = true;
  top.center_offset = Eigen::Vector3d(0.0, 0.0, 0.5);
  top.forces = {Gravity{Eigen::Vector3d(0.0, 0.0, -9.81)}};
  return top;
}

/// The body-frame angular velocity J^-1 R^T L.
inline Eigen::Vector3d body_omega(const BodyModel& body, const BodyState& s) {
  return (s.orientation.conjugate() * s.angular_momentum).cwiseQuotient(body.moments);
}

/// The rotational kinetic energy w . J w / 2.
inline double rotational_energy(const BodyModel& body, const BodyState& s) {
  const Eigen::Vector3d w = body_omega(body, s);
  return 0.5 * w.dot(body.moments.cwiseProduct(w));
}

/// Runs `steps` fixed steps of `kind` from `s`.
inline BodyState run(IntegratorKind kind, const BodyModel& body, BodyState s, double h, int steps,
                     double tolerance = 1e-10) {
  StepSettings settings;
  settings.tolerance = tolerance;
  const auto stepper = make_stepper(kind, body, s, settings);
  for (int i = 0; i < steps; ++i) stepper->step(s, i * h, h);
  return s;
}

}  // namespace tumble::engine::fixtures
