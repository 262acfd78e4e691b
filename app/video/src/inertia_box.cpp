// The box of equal inertia.
#include "app/video/inertia_box.hpp"

#include <algorithm>
#include <cmath>

#include "engine/mass/principal_frame.hpp"

namespace tumble::app {

InertiaBox equal_inertia_box(const engine::MassProperties& properties) {
  const engine::PrincipalFrame principal = engine::principal_frame(properties.inertia);
  const Eigen::Vector3d& moments = principal.moments;
  InertiaBox box;
  box.center = properties.center_of_mass;
  box.axes = principal.axes;
  for (int i = 0; i < 3; ++i) {
    const double excess = moments.sum() - 2.0 * moments[i];  // I_j + I_k - I_i
    box.sides[i] = std::sqrt(std::max(0.0, 6.0 * excess / properties.mass));
  }
  return box;
}

}  // namespace tumble::app
