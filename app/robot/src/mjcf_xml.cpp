// Attributes, numbers and orientations of MJCF elements.
#include "mjcf_xml.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>

#include "base/errors.hpp"

namespace tumble::app::robot::mjcf {
namespace {

bool is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r';
}

/// One rotation of an Euler sequence: `axis` x, y or z (either case), `angle` in radians.
Eigen::Matrix3d axis_rotation(char axis, double angle) {
  const char lower = static_cast<char>(axis | 0x20);
  const Eigen::Vector3d unit = lower == 'x'   ? Eigen::Vector3d::UnitX()
                               : lower == 'y' ? Eigen::Vector3d::UnitY()
                                              : Eigen::Vector3d::UnitZ();
  return Eigen::AngleAxisd(angle, unit).toRotationMatrix();
}

/// MuJoCo's xyaxes: x normalised, y made orthogonal to it and normalised, z = x cross y.
std::optional<Eigen::Matrix3d> from_xyaxes(const std::vector<double>& v) {
  Eigen::Vector3d x(v[0], v[1], v[2]);
  Eigen::Vector3d y(v[3], v[4], v[5]);
  if (x.norm() < 1e-12) return std::nullopt;
  x.normalize();
  y -= x * x.dot(y);
  if (y.norm() < 1e-12) return std::nullopt;
  y.normalize();
  Eigen::Matrix3d out;
  out << x, y, x.cross(y);
  return out;
}

/// The rotation of one orientation attribute's numbers; unset when they give none (a zero
/// quaternion or axis).
std::optional<Eigen::Matrix3d> rotation_of(const std::string& name, const std::vector<double>& v,
                                           const Compiler& compiler) {
  const double unit = compiler.degrees ? std::numbers::pi / 180.0 : 1.0;
  if (name == "quat") {
    const Eigen::Quaterniond q(v[0], v[1], v[2], v[3]);
    if (q.norm() < 1e-12) return std::nullopt;
    return q.normalized().toRotationMatrix();
  }
  if (name == "axisangle") {
    const Eigen::Vector3d axis(v[0], v[1], v[2]);
    if (axis.norm() < 1e-12) return std::nullopt;
    return Eigen::AngleAxisd(v[3] * unit, axis.normalized()).toRotationMatrix();
  }
  if (name == "euler") {
    Eigen::Matrix3d out = Eigen::Matrix3d::Identity();
    for (std::size_t i = 0; i < 3; ++i) {
      const char axis = compiler.eulerseq[i];
      const Eigen::Matrix3d turn = axis_rotation(axis, v[i] * unit);
      // Lowercase: about the rotating (new) axes; uppercase: about the fixed ones.
      out = (axis >= 'a') ? Eigen::Matrix3d(out * turn) : Eigen::Matrix3d(turn * out);
    }
    return out;
  }
  if (name == "xyaxes") return from_xyaxes(v);
  const Eigen::Vector3d z(v[0], v[1], v[2]);
  if (z.norm() < 1e-12) return std::nullopt;
  return z_to(z);
}

std::size_t orientation_count(const std::string& name) {
  if (name == "xyaxes") return 6;
  if (name == "zaxis") return 3;
  if (name == "euler") return 3;
  return 4;
}

}  // namespace

std::string Source::at(pugi::xml_node node) const {
  const auto offset = static_cast<std::size_t>(std::max<std::ptrdiff_t>(node.offset_debug(), 0));
  const auto end = text->begin() + static_cast<std::ptrdiff_t>(std::min(offset, text->size()));
  const auto line = std::count(text->begin(), end, '\n') + 1;
  return file.string() + ": line " + std::to_string(line) + ": ";
}

void Source::fail(pugi::xml_node node, const std::string& what) const {
  throw InputError(at(node) + what);
}

std::optional<std::string> Attributes::get(const char* name) const {
  if (const pugi::xml_attribute a = node.attribute(name)) return std::string(a.value());
  if (inherited) {
    if (const auto it = inherited->find(name); it != inherited->end()) return it->second;
  }
  return std::nullopt;
}

bool Attributes::own(const char* name) const {
  return static_cast<bool>(node.attribute(name));
}

std::vector<double> parse_numbers(const std::string& value, std::size_t least, std::size_t most,
                                  const Source& source, pugi::xml_node node,
                                  const std::string& where, const char* name) {
  std::vector<double> out;
  const std::string prefix = where + ": " + name + ": ";
  std::size_t at = 0;
  while (true) {
    while (at < value.size() && is_blank(value[at])) ++at;
    if (at == value.size()) break;
    std::size_t end = at;
    while (end < value.size() && !is_blank(value[end])) ++end;
    const std::size_t start = value[at] == '+' ? at + 1 : at;
    double number = 0.0;
    const auto result = std::from_chars(value.data() + start, value.data() + end, number);
    if (result.ec != std::errc() || result.ptr != value.data() + end || !std::isfinite(number)) {
      source.fail(node, prefix + "'" + value.substr(at, end - at) + "' is not a finite number");
    }
    out.push_back(number);
    at = end;
  }
  if (out.size() < least || out.size() > most) {
    const std::string wanted = least == most
                                   ? std::to_string(least)
                                   : std::to_string(least) + " to " + std::to_string(most);
    source.fail(node, prefix + "expected " + wanted + " numbers, got " +
                          std::to_string(out.size()) + " ('" + value + "')");
  }
  return out;
}

std::optional<Eigen::Matrix3d> orientation(const Attributes& attributes, const Compiler& compiler,
                                           const Source& source, const std::string& where) {
  // The element's own orientation replaces its class's whatever attribute either uses.
  bool own = false;
  for (const char* name : kOrientationAttributes) own = own || attributes.own(name);
  const Attributes looked = own ? Attributes{attributes.node, nullptr} : attributes;
  std::optional<std::string> chosen;
  std::string value;
  for (const char* name : kOrientationAttributes) {
    const std::optional<std::string> v = looked.get(name);
    if (!v) continue;
    if (chosen) {
      source.fail(attributes.node, where + ": " + *chosen + " and " + name +
                                       " both give the orientation (give only one)");
    }
    chosen = name;
    value = *v;
  }
  if (!chosen) return std::nullopt;
  const std::size_t count = orientation_count(*chosen);
  const std::vector<double> numbers =
      parse_numbers(value, count, count, source, attributes.node, where, chosen->c_str());
  const std::optional<Eigen::Matrix3d> rotation = rotation_of(*chosen, numbers, compiler);
  if (!rotation) {
    source.fail(attributes.node,
                where + ": " + *chosen + ": '" + value + "' gives no rotation (a zero vector)");
  }
  return rotation;
}

Eigen::Matrix3d z_to(const Eigen::Vector3d& direction) {
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d d = direction.normalized();
  const Eigen::Vector3d axis = z.cross(d);
  const double sine = axis.norm();
  if (sine < 1e-14) {
    return d.z() > 0
               ? Eigen::Matrix3d::Identity()
               : Eigen::AngleAxisd(std::numbers::pi, Eigen::Vector3d::UnitX()).toRotationMatrix();
  }
  return Eigen::AngleAxisd(std::atan2(sine, z.dot(d)), axis / sine).toRotationMatrix();
}

}  // namespace tumble::app::robot::mjcf
