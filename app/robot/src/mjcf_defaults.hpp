#pragma once
/// @file MJCF default classes: the attributes each class gives geoms and meshes, nested
/// classes inheriting their parent's and overriding them (the top class is "main").

#include <map>
#include <string>

#include <pugixml.hpp>

#include "mjcf_xml.hpp"

namespace tumble::app::robot::mjcf {

/// One default class, its parents' attributes included.
struct DefaultClass {
  AttributeMap geom;
  AttributeMap mesh;
};

/// All default classes of a model.
class Defaults {
 public:
  /// Reads the <default> elements under `root` (<mujoco>). A nested class must have a name;
  /// two classes of one name are an error.
  Defaults(pugi::xml_node root, const Source& source);

  /// The class named `name`, for `node` (whose class it is). Throws "FILE: line N: WHERE:
  /// unknown class 'NAME'" when no <default> defines it.
  const DefaultClass& get(const std::string& name, pugi::xml_node node, const Source& source,
                          const std::string& where) const;

 private:
  void read(pugi::xml_node element, const DefaultClass& parent, bool top, const Source& source);

  std::map<std::string, DefaultClass, std::less<>> classes_;
};

/// MuJoCo's size of an element whose class gives `inherited` and that itself gives `own`: the
/// own numbers replace the first ones of the class's, the rest stay ("0.1" over "1 2 3" is
/// "0.1 2 3"). Either may be empty.
std::string merged_size(const std::string& inherited, const std::string& own);

}  // namespace tumble::app::robot::mjcf
