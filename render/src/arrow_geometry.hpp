#pragma once
// Unit shapes the arrows are drawn from, generated once per renderer.

#include <Eigen/Core>

#include "render/draw_list.hpp"

namespace tumble::render::detail {

/// Cylinder of radius 1 from z = 0 to z = 1, capped at both ends, smooth sides.
MeshData unit_cylinder(int segments);

/// Cone with a base of radius 1 at z = 0 and its apex at (0, 0, 1), base capped.
MeshData unit_cone(int segments);

/// Body-to-world transforms of an arrow's shaft (unit cylinder) and head (unit cone).
struct ArrowTransforms {
  Eigen::Matrix4f shaft;
  Eigen::Matrix4f head;
};

/// Places the arrow: head length 4.5 x thickness (at most 40 % of the arrow), head radius
/// 1.6 x thickness. Returns false for a zero-length arrow (nothing to draw).
bool arrow_transforms(const Arrow& arrow, ArrowTransforms& out);

}  // namespace tumble::render::detail
