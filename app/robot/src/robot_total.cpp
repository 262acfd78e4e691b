// The whole robot's mass properties in its zero configuration.
#include "app/robot/robot_total.hpp"

namespace tumble::app::robot {

std::optional<RobotTotal> robot_total(
    const std::vector<Link>& links,
    const std::vector<std::optional<engine::MassProperties>>& inertials) {
  RobotTotal out;
  std::vector<engine::MassProperties> parts;
  for (std::size_t i = 0; i < links.size(); ++i) {
    if (!inertials[i] || !(inertials[i]->mass > 0.0)) {
      out.left_out.push_back(links[i].name);
      continue;
    }
    const Eigen::Isometry3d& frame = links[i].frame;
    parts.push_back(inertials[i]->rotated(frame.linear()).translated(frame.translation()));
  }
  if (parts.empty()) return std::nullopt;
  out.counted = parts.size();
  out.properties = engine::combined(parts);
  return out;
}

}  // namespace tumble::app::robot
