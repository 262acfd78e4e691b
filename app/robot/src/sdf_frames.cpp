// SDF's frames: each link, frame and joint of a model placed relative to another.
#include "sdf_frames.hpp"

#include <numbers>
#include <utility>
#include <vector>

#include "app/robot/inertial_xml.hpp"
#include "base/errors.hpp"
#include "xml_values.hpp"

namespace tumble::app::robot {

/// A <pose> element's value (absent: the identity), in the frame its relative_to names.
Eigen::Isometry3d sdf_pose_value(const pugi::xml_node& pose, const std::string& where) {
  if (!pose) return Eigen::Isometry3d::Identity();
  const std::string format = pose.attribute("rotation_format").value();
  const bool quaternion = format == "quat_xyzw";
  if (!format.empty() && !quaternion && format != "euler_rpy") {
    throw InputError(where + ": pose rotation_format '" + format +
                     "': expected euler_rpy or quat_xyzw");
  }
  const std::vector<double> v =
      parse_numbers(pose.text().get(), {quaternion ? 7u : 6u}, where + ": pose");
  const Eigen::Vector3d xyz(v[0], v[1], v[2]);
  if (quaternion) {
    const Eigen::Quaterniond q(v[6], v[3], v[4], v[5]);
    if (q.norm() == 0.0) throw InputError(where + ": pose: the quaternion is zero");
    return pose_from(xyz, q.normalized().toRotationMatrix());
  }
  Eigen::Vector3d rpy(v[3], v[4], v[5]);
  if (std::string(pose.attribute("degrees").value()) == "true") rpy *= std::numbers::pi / 180.0;
  return pose_from(xyz, rotation_from_rpy(rpy));
}

SdfModelFrames::SdfModelFrames(const pugi::xml_node& model, const Eigen::Isometry3d& model_frame,
                               std::string where)
    : model_frame_(model_frame), where_(std::move(where)) {
  for (const pugi::xml_node child : model.children()) {
    const std::string kind = child.name();
    if (kind != "link" && kind != "frame" && kind != "joint") continue;
    const std::string name = child.attribute("name").value();
    if (name.empty()) continue;  // the readers refuse a nameless link themselves
    Named named;
    named.what = kind + " '" + name + "'";
    const pugi::xml_node pose = child.child("pose");
    named.pose = sdf_pose_value(pose, where_ + ": " + named.what);
    named.relative_to = pose.attribute("relative_to").value();
    if (named.relative_to.empty() && kind == "frame") {
      named.relative_to = child.attribute("attached_to").value();
    }
    if (named.relative_to.empty() && kind == "joint") {
      named.relative_to = child.child("child").text().get();
    }
    if (named.relative_to.empty()) named.relative_to = "__model__";
    named_.emplace(name, std::move(named));
  }
}

Eigen::Isometry3d SdfModelFrames::resolve(const std::string& name) const {
  if (name != "__model__" && !named_.contains(name)) {
    throw InputError(where_ + ": no link, frame or joint '" + name + "' in the model");
  }
  return resolve(name, 0);
}

Eigen::Isometry3d SdfModelFrames::resolve(const std::string& name, std::size_t depth) const {
  if (name == "__model__") return model_frame_;
  const Named& named = named_.find(name)->second;
  const std::string at = where_ + ": " + named.what + ": placed relative to '" + named.relative_to;
  if (depth > named_.size()) throw InputError(at + "': the poses refer to each other in a cycle");
  if (named.relative_to != "__model__" && !named_.contains(named.relative_to)) {
    throw InputError(at +
                     "': no link, frame or joint of that name in the model (names in "
                     "nested models are not followed)");
  }
  return resolve(named.relative_to, depth + 1) * named.pose;
}

}  // namespace tumble::app::robot
