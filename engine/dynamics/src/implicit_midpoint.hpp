#pragma once
// Private to the engine: the right-hand side of the implicit midpoint rule and its Jacobian
// (engine/PHYSICS.md §3, `midpoint`), exposed for the finite-difference check of the tests.

#include <Eigen/Core>

#include "engine/body/rigid_body.hpp"

namespace tumble::engine::steppers::implicit_midpoint {

/// y = (x, v, q, L_b): position, velocity, orientation as four numbers (w, x, y, z; not
/// necessarily unit), body-frame angular momentum.
using Vector13 = Eigen::Matrix<double, 13, 1>;
using Matrix13 = Eigen::Matrix<double, 13, 13>;

/// y of a state (q as stored, L_b = R^T L).
Vector13 pack(const BodyState& s);

/// f(y): dx/dt = v (0 when pivoted), dv/dt = F / m (0 when pivoted),
/// dq/dt = 1/2 q (0, J^-1 L_b), dL_b/dt = L_b x w_b + R^T tau, with R and the forces taken at
/// q / |q|.
Vector13 rate(const BodyModel& body, const Vector13& y);

/// df/dy at y, analytic (gravity, constant torques, spring-dampers; the normalisation of q).
Matrix13 rate_jacobian(const BodyModel& body, const Vector13& y);

}  // namespace tumble::engine::steppers::implicit_midpoint
