// An origin-free energy scale (engine/PHYSICS.md §6): what the blow-up rule and the stability
// classes divide energy errors by, so that moving a scene or a potential's zero changes nothing.
#include <algorithm>
#include <variant>

#include "engine/body/rigid_body.hpp"

namespace tumble::engine {

double energy_scale(const BodyModel& body, const BodyState& state, double duration) {
  const double rotational = 0.5 * angular_velocity(body, state).dot(state.angular_momentum);
  double translational = body.pivoted ? 0.0 : 0.5 * body.mass * state.velocity.squaredNorm();
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  bool has_gravity = false;
  double springs = 0.0, stiffness = 0.0;
  for (const ForceTerm& term : body.forces) {
    if (const auto* gravity = std::get_if<Gravity>(&term)) {
      g += gravity->acceleration;
      has_gravity = true;
    } else if (const auto* spring = std::get_if<Spring>(&term)) {
      // k/2 |P - a|^2 is its own swing: its minimum, 0, is reached at the anchor.
      const Eigen::Vector3d point =
          rotation_centre(body, state) + state.orientation * spring->attach;
      springs += 0.5 * spring->stiffness * (point - spring->anchor).squaredNorm();
      stiffness += spring->stiffness;
    }
  }
  double swing = 0.0;
  if (has_gravity) {
    const double m = body.mass;
    if (body.pivoted) {
      // U = -m g . (pivot + R c) is lowest with R c along g: U - U_min = m |g| l - m g . (R c).
      const Eigen::Vector3d arm = state.orientation * body.center_offset;
      swing = std::max(0.0, m * g.norm() * arm.norm() - m * g.dot(arm));
    } else if (stiffness > 0.0) {
      // Hung on springs the body sags by m |g| / K; gravity's work down to that equilibrium is
      // m^2 |g|^2 / K. With the springs' own energy this is within a factor 2 of E - U_min
      // (1D: k/2 (y0 - y*)^2 <= k y0^2 + k y*^2).
      swing = m * m * g.squaredNorm() / stiffness;
    } else {
      // No minimum: the exact fall v(t) = v + g t releases potential as kinetic energy, whose
      // largest value over [0, duration] is at an end (|v + g t|^2 is convex in t).
      translational =
          0.5 * m *
          std::max(state.velocity.squaredNorm(), (state.velocity + g * duration).squaredNorm());
    }
  }
  return rotational + translational + springs + swing;
}

}  // namespace tumble::engine
