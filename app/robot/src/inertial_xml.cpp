// Inertial elements for URDF, SDF and MJCF.
#include "app/robot/inertial_xml.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>

#include <Eigen/Geometry>

#include "engine/mass/principal_frame.hpp"

namespace tumble::app::robot {
namespace {

std::string numbers(const Eigen::Ref<const Eigen::VectorXd>& values) {
  std::string out;
  for (Eigen::Index i = 0; i < values.size(); ++i) out += (i ? " " : "") + xml_number(values[i]);
  return out;
}

std::string attribute(const char* name, const std::string& value) {
  return std::string(" ") + name + "=\"" + value + "\"";
}

/// The inertia to write, and the rotation of its frame in the link's frame.
struct Written {
  Eigen::Matrix3d inertia;
  Eigen::Matrix3d rotation;
};

Written written(const engine::MassProperties& properties, InertialFrame frame) {
  if (frame == InertialFrame::mesh) return {properties.inertia, Eigen::Matrix3d::Identity()};
  const engine::PrincipalFrame principal = engine::principal_frame(properties.inertia);
  return {principal.moments.asDiagonal(), principal.axes};
}

std::string urdf(const engine::MassProperties& p, const Written& w, const std::string& indent,
                 const std::string& step) {
  const Eigen::Matrix3d& I = w.inertia;
  std::string out = "<inertial>\n";
  out += indent + step + "<origin" + attribute("xyz", numbers(p.center_of_mass)) +
         attribute("rpy", numbers(roll_pitch_yaw(w.rotation))) + "/>\n";
  out += indent + step + "<mass" + attribute("value", xml_number(p.mass)) + "/>\n";
  out += indent + step + "<inertia" + attribute("ixx", xml_number(I(0, 0))) +
         attribute("ixy", xml_number(I(0, 1))) + attribute("ixz", xml_number(I(0, 2))) +
         attribute("iyy", xml_number(I(1, 1))) + attribute("iyz", xml_number(I(1, 2))) +
         attribute("izz", xml_number(I(2, 2))) + "/>\n";
  return out + indent + "</inertial>";
}

std::string sdf(const engine::MassProperties& p, const Written& w, const std::string& indent,
                const std::string& step) {
  const Eigen::Matrix3d& I = w.inertia;
  Eigen::Matrix<double, 6, 1> pose;
  pose << p.center_of_mass, roll_pitch_yaw(w.rotation);
  std::string out = "<inertial>\n";
  out += indent + step + "<pose>" + numbers(pose) + "</pose>\n";
  out += indent + step + "<mass>" + xml_number(p.mass) + "</mass>\n";
  out += indent + step + "<inertia>\n";
  const std::array<std::pair<const char*, double>, 6> elements = {{{"ixx", I(0, 0)},
                                                                   {"ixy", I(0, 1)},
                                                                   {"ixz", I(0, 2)},
                                                                   {"iyy", I(1, 1)},
                                                                   {"iyz", I(1, 2)},
                                                                   {"izz", I(2, 2)}}};
  for (const auto& [name, value] : elements) {
    out += indent + step + step + "<" + name + ">" + xml_number(value) + "</" + name + ">\n";
  }
  out += indent + step + "</inertia>\n";
  return out + indent + "</inertial>";
}

std::string mjcf(const engine::MassProperties& p, const Written& w, InertialFrame frame) {
  std::string out = "<inertial" + attribute("pos", numbers(p.center_of_mass));
  out += attribute("mass", xml_number(p.mass));
  const Eigen::Matrix3d& I = w.inertia;
  if (frame == InertialFrame::mesh) {
    Eigen::Matrix<double, 6, 1> full;
    full << I(0, 0), I(1, 1), I(2, 2), I(0, 1), I(0, 2), I(1, 2);
    out += attribute("fullinertia", numbers(full));
  } else {
    const Eigen::Quaterniond q(w.rotation);
    out += attribute("quat", numbers(Eigen::Vector4d(q.w(), q.x(), q.y(), q.z())));
    out += attribute("diaginertia", numbers(I.diagonal()));
  }
  return out + "/>";
}

}  // namespace

std::string xml_number(double value) {
  if (value == 0.0) return "0";
  std::array<char, 64> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  return std::string(buffer.data(), result.ptr);
}

Eigen::Vector3d roll_pitch_yaw(const Eigen::Matrix3d& R) {
  // Pitch from atan2, not asin(-R(2, 0)), which loses half the digits near +-pi/2. Near the
  // lock, yaw from the first column is mostly rounding noise and only roll -+ yaw is defined,
  // so roll is solved from what is left once yaw and pitch are undone, Rx(roll) =
  // Ry(pitch)^T Rz(yaw)^T R: the angles then rebuild R to rounding at any pitch. At the lock
  // itself (first column's xy below 1e-15: rebuilt to 3e-15 either way) yaw takes the
  // whole turn and roll is zero.
  const double cos_pitch = std::hypot(R(0, 0), R(1, 0));
  const double pitch = std::atan2(-R(2, 0), cos_pitch);
  const double yaw =
      cos_pitch < 1e-15 ? std::atan2(-R(0, 1), R(1, 1)) : std::atan2(R(1, 0), R(0, 0));
  const Eigen::Matrix3d rest = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                                Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()))
                                   .toRotationMatrix()
                                   .transpose() *
                               R;
  const double roll = std::atan2(rest(2, 1) - rest(1, 2), rest(1, 1) + rest(2, 2));
  return {roll, pitch, yaw};
}

Eigen::Matrix3d rotation_from_rpy(const Eigen::Vector3d& rpy) {
  return (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

std::string inertial_element(RobotFormat format, const engine::MassProperties& properties,
                             InertialFrame frame, const std::string& indent,
                             const std::string& step) {
  const Written w = written(properties, frame);
  switch (format) {
    case RobotFormat::urdf:
      return urdf(properties, w, indent, step);
    case RobotFormat::sdf:
      return sdf(properties, w, indent, step);
    case RobotFormat::mjcf:
      return mjcf(properties, w, frame);
  }
  return {};
}

}  // namespace tumble::app::robot
