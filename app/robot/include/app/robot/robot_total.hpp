#pragma once
/// @file The whole robot's mass properties in its zero configuration (every joint at zero):
/// each link's inertial carried into the model's frame by Link::frame (its centre of mass
/// moved, its tensor rotated, R I R^T), then summed about their common centre of mass by the
/// parallel-axis theorem.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "app/robot/robot_model.hpp"
#include "engine/mass/mass_properties.hpp"

namespace tumble::app::robot {

/// What the links add up to.
struct RobotTotal {
  /// In the model's frame: total mass, centre of mass, inertia about that centre (model axes).
  engine::MassProperties properties;
  std::size_t counted = 0;            ///< links whose inertial went in
  std::vector<std::string> left_out;  ///< links with no inertial to count (names)
};

/// The total of `inertials` (one per link of `links`, in the link's frame; unset: the link is
/// left out); unset when no link has a positive mass.
std::optional<RobotTotal> robot_total(
    const std::vector<Link>& links,
    const std::vector<std::optional<engine::MassProperties>>& inertials);

}  // namespace tumble::app::robot
