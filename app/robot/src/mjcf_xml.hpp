#pragma once
/// @file What the parts of the MJCF reader share: the file being read (for messages that name
/// file, line and attribute), the compiler's settings, an element's attributes with those its
/// default class gives, and numbers and orientations read from them as MuJoCo reads them.

#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <pugixml.hpp>

namespace tumble::app::robot::mjcf {

/// The file being read.
struct Source {
  std::filesystem::path file;
  const std::string* text = nullptr;

  /// "FILE: line N: " for the element (N counted from 1).
  std::string at(pugi::xml_node node) const;
  /// Throws InputError "FILE: line N: WHAT".
  [[noreturn]] void fail(pugi::xml_node node, const std::string& what) const;
};

/// What <compiler> sets that matters here (MuJoCo's defaults).
struct Compiler {
  bool degrees = true;            ///< angle="degree" (MuJoCo's default) or "radian"
  std::string eulerseq = "xyz";   ///< lowercase: rotating axes; uppercase: fixed axes
  std::filesystem::path meshdir;  ///< where mesh files are, the model file's folder when unset
  bool strippath = false;         ///< keep only the file name of mesh paths
  int group_first = 0;            ///< inertiagrouprange: geoms of other groups have no mass
  int group_last = 5;
  /// inertiafromgeom: "true" (MuJoCo ignores every <inertial>), "false" or "auto" (default).
  std::string inertiafromgeom = "auto";
};

/// Attribute name to value, as a default class gives them to one kind of element.
using AttributeMap = std::map<std::string, std::string, std::less<>>;

/// An element's attributes as MuJoCo sees them: its own, else its default class's.
struct Attributes {
  pugi::xml_node node;
  const AttributeMap* inherited = nullptr;

  /// The value of `name`, own or inherited; unset when neither gives it.
  std::optional<std::string> get(const char* name) const;
  /// Whether the element itself gives `name`.
  bool own(const char* name) const;
};

/// The numbers of an attribute's value. Throws "FILE: line N: WHERE: NAME: ..." when one is
/// not a finite number or there are not between `least` and `most` of them.
std::vector<double> parse_numbers(const std::string& value, std::size_t least, std::size_t most,
                                  const Source& source, pugi::xml_node node,
                                  const std::string& where, const char* name);

/// The rotation the element's orientation gives (quat, axisangle, euler, xyaxes or zaxis, at
/// most one of them; the element's own before its class's), or unset when none is given.
/// Angles are in the compiler's unit. Throws naming the attribute.
std::optional<Eigen::Matrix3d> orientation(const Attributes& attributes, const Compiler& compiler,
                                           const Source& source, const std::string& where);

/// The rotation taking z to `direction` by the shortest way (MuJoCo's zaxis and fromto); a
/// half turn about x when `direction` is -z.
Eigen::Matrix3d z_to(const Eigen::Vector3d& direction);

/// The attributes that give an orientation, in the order MuJoCo lists them.
inline constexpr const char* kOrientationAttributes[] = {"quat", "axisangle", "euler", "xyaxes",
                                                         "zaxis"};

}  // namespace tumble::app::robot::mjcf
