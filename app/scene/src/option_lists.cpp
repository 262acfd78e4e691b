// Comma-separated command-line lists.
#include "app/scene/option_lists.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "app/scene/scene.hpp"
#include "base/errors.hpp"

namespace tumble::app {

using tumble::InputError;

std::vector<std::string> split_option_list(const std::string& text, const char* option) {
  const auto fail = [&] {
    throw InputError(std::string(option) +
                     ": expected a comma-separated list without empty items, got '" + text + "'");
  };
  std::vector<std::string> items;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    const auto first = item.find_first_not_of(" \t");
    if (first == std::string::npos) fail();
    items.push_back(item.substr(first, item.find_last_not_of(" \t") - first + 1));
  }
  if (items.empty() || text.back() == ',') fail();
  return items;
}

std::vector<double> parse_positive_list(const std::string& text, const char* option) {
  std::vector<double> values;
  for (const std::string& item : split_option_list(text, option)) {
    char* end = nullptr;
    const double value = std::strtod(item.c_str(), &end);
    if (end == item.c_str() || *end != '\0' || !std::isfinite(value) || !(value > 0.0)) {
      throw InputError(std::string(option) + ": expected a positive number, got '" + item + "'");
    }
    values.push_back(value);
  }
  return values;
}

std::vector<const engine::IntegratorInfo*> parse_integrator_list(const std::string& text,
                                                                 const char* option) {
  std::vector<const engine::IntegratorInfo*> chosen;
  for (const std::string& name : split_option_list(text, option)) {
    const auto kind = engine::integrator_from_name(name);
    if (!kind) {
      throw InputError(std::string(option) + ": unknown integrator '" + name +
                       "'; expected one of: " + integrator_names());
    }
    const engine::IntegratorInfo* info = &engine::integrator_info(*kind);
    if (std::find(chosen.begin(), chosen.end(), info) == chosen.end()) chosen.push_back(info);
  }
  return chosen;
}

}  // namespace tumble::app
