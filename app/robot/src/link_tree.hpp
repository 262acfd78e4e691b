#pragma once
/// @file The kinematic tree of a robot file's links: each joint names a parent link and a child
/// link, and (URDF) the child's frame in the parent's in the zero configuration. Fills
/// Link::parent and, when asked, Link::frame as the product of joint origins from the root.

#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "app/robot/robot_model.hpp"

namespace tumble::app::robot {

/// One joint as the tree needs it.
struct JointEdge {
  std::string name;    ///< for messages: "joint 'elbow'"
  std::string parent;  ///< a link's name
  std::string child;   ///< a link's name
  /// The child link's frame in the parent link's frame with the joint at zero.
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();
};

/// Sets each child link's `parent` from `joints` and, when `compose_frames`, its `frame` as
/// the parent's frame times the joint's origin (roots keep their frame). Throws InputError
/// "FILE: joint 'J': ..." when a joint names a link that is not in `links`, a link has two
/// parents, or the joints form a cycle.
void build_link_tree(std::vector<Link>& links, const std::vector<JointEdge>& joints,
                     const std::string& file, bool compose_frames);

}  // namespace tumble::app::robot
