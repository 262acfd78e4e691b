// MJCF default classes.
#include "mjcf_defaults.hpp"

#include <sstream>
#include <vector>

namespace tumble::app::robot::mjcf {
namespace {

std::vector<std::string> words(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> out;
  for (std::string word; in >> word;) out.push_back(word);
  return out;
}

/// `element`'s attributes laid over `into` (orientation and size as MuJoCo combines them).
void override_with(AttributeMap& into, pugi::xml_node element) {
  bool orients = false;
  for (const char* name : kOrientationAttributes) orients = orients || element.attribute(name);
  if (orients) {
    for (const char* name : kOrientationAttributes) into.erase(name);
  }
  for (const pugi::xml_attribute a : element.attributes()) {
    const std::string name = a.name();
    if (name == "size") {
      const auto it = into.find(name);
      into[name] = merged_size(it == into.end() ? "" : it->second, a.value());
    } else {
      into[name] = a.value();
    }
  }
}

}  // namespace

std::string merged_size(const std::string& inherited, const std::string& own) {
  std::vector<std::string> out = words(inherited);
  const std::vector<std::string> mine = words(own);
  if (out.size() < mine.size()) out.resize(mine.size());
  for (std::size_t i = 0; i < mine.size(); ++i) out[i] = mine[i];
  std::string joined;
  for (const std::string& word : out) joined += (joined.empty() ? "" : " ") + word;
  return joined;
}

Defaults::Defaults(pugi::xml_node root, const Source& source) {
  classes_["main"] = {};
  for (const pugi::xml_node element : root.children("default")) {
    read(element, classes_["main"], true, source);
  }
}

void Defaults::read(pugi::xml_node element, const DefaultClass& parent, bool top,
                    const Source& source) {
  const pugi::xml_attribute named = element.attribute("class");
  if (!named && !top) source.fail(element, "<default>: a nested default class needs a class name");
  const std::string name = named ? named.value() : "main";
  if (classes_.count(name) && (name != "main" || !top)) {
    source.fail(element, "<default>: class '" + name + "' is defined twice");
  }
  DefaultClass own = parent;
  for (const pugi::xml_node child : element.children()) {
    const std::string kind = child.name();
    if (kind == "geom") override_with(own.geom, child);
    if (kind == "mesh") override_with(own.mesh, child);
  }
  classes_[name] = own;
  for (const pugi::xml_node child : element.children("default")) {
    read(child, classes_[name], false, source);
  }
}

const DefaultClass& Defaults::get(const std::string& name, pugi::xml_node node,
                                  const Source& source, const std::string& where) const {
  const auto it = classes_.find(name);
  if (it == classes_.end()) {
    source.fail(node, where + ": unknown class '" + name + "' (no <default class=\"" + name +
                          "\"> defines it)");
  }
  return it->second;
}

}  // namespace tumble::app::robot::mjcf
