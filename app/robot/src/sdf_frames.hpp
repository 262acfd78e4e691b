#pragma once
/// @file SDF's frames (SDFormat 1.7 pose semantics): within a model, each link, <frame> and
/// joint is placed by a <pose> relative to another of them (relative_to; a frame defaults to
/// its attached_to, a joint to its child link, everything else to the model, "__model__").
/// Resolving the names gives each link's frame in the model's frame.

#include <map>
#include <string>

#include <Eigen/Geometry>
#include <pugixml.hpp>

namespace tumble::app::robot {

/// A <pose> element's value (absent: the identity), in the frame its relative_to names: xyz
/// and roll-pitch-yaw (radians, or degrees="true"), or xyz and a quaternion xyzw
/// (rotation_format="quat_xyzw"). Throws InputError "WHERE: pose: ..." on bad numbers.
Eigen::Isometry3d sdf_pose_value(const pugi::xml_node& pose, const std::string& where);

/// The named frames of one <model>, resolved on demand.
class SdfModelFrames {
 public:
  /// Reads the poses of the links, frames and joints of `model` (not of models nested in
  /// it); `model_frame` is the model's frame in the frame the result is wanted in, `where`
  /// names the file (and the model) in messages.
  SdfModelFrames(const pugi::xml_node& model, const Eigen::Isometry3d& model_frame,
                 std::string where);

  /// The frame named `name` (a link, frame or joint of the model, or "__model__"). Throws
  /// InputError "WHERE: NAME: pose relative_to 'OTHER': ..." when a name is unknown or the
  /// poses refer to each other in a cycle.
  Eigen::Isometry3d resolve(const std::string& name) const;

 private:
  struct Named {
    Eigen::Isometry3d pose;
    std::string relative_to;  ///< "__model__" when the pose names none
    std::string what;         ///< "link 'arm'", for messages
  };
  Eigen::Isometry3d resolve(const std::string& name, std::size_t depth) const;
  std::map<std::string, Named, std::less<>> named_;
  Eigen::Isometry3d model_frame_;
  std::string where_;
};

}  // namespace tumble::app::robot
