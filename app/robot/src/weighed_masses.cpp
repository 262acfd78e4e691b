// Weighed masses: --mass LINK=M checked against the file's links, and --total-mass M spread
// over the links in proportion to their computed masses.
#include <algorithm>
#include <cstdio>
#include <string>

#include "app/robot/link_inertial.hpp"
#include "base/errors.hpp"

namespace tumble::app::robot {
namespace {

/// "%g" of a mass, for messages.
std::string kilograms(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

/// Throws when an entry of `entries` (the values of `option`) names no link of `robot`.
void check_names(const Robot& robot, const std::vector<std::pair<std::string, double>>& entries,
                 const char* option) {
  for (const auto& entry : entries) {
    const std::string& name = entry.first;  // a named variable: lambdas cannot capture bindings
    const bool found = std::any_of(robot.links.begin(), robot.links.end(),
                                   [&](const Link& link) { return link.name == name; });
    if (!found) {
      throw InputError(std::string(option) + " '" + name + "=" + kilograms(entry.second) +
                       "': no link '" + name + "' in " + robot.file.string());
    }
  }
}

}  // namespace

std::optional<double> value_for(const std::vector<std::pair<std::string, double>>& entries,
                                const std::string& name) {
  std::optional<double> out;
  for (const auto& [link, value] : entries) {
    if (link == name) out = value;
  }
  return out;
}

void check_link_options(const Robot& robot, const ComputeOptions& options) {
  check_names(robot, options.link_densities, "--density");
  check_names(robot, options.link_masses, "--mass");
}

void spread_total_mass(const std::vector<Link>& links, std::vector<LinkInertial>& results,
                       const ComputeOptions& options) {
  if (!options.total_mass) return;
  const double total = *options.total_mass;
  double fixed = 0.0;   // --mass links, and stated masses kept on links without geometry
  double shared = 0.0;  // the computed masses the rest is spread over
  for (std::size_t i = 0; i < links.size(); ++i) {
    const LinkInertial& result = results[i];
    if (result.computed && result.mass_from == "--mass") {
      fixed += result.computed->mass;
    } else if (result.computed) {
      shared += result.computed->mass;
    } else if (!result.error && links[i].stated && links[i].stated->mass &&
               *links[i].stated->mass > 0.0) {
      fixed += *links[i].stated->mass;
    }
  }
  const std::string at = "--total-mass " + kilograms(total) + ": ";
  if (fixed >= total) {
    throw InputError(at +
                     "the links' fixed masses (--mass, and the stated masses of links "
                     "without geometry) already make " +
                     kilograms(fixed) + " kg");
  }
  if (shared <= 0.0) throw InputError(at + "no link computed from its geometry to spread it over");
  const double factor = (total - fixed) / shared;
  for (LinkInertial& result : results) {
    if (!result.computed || result.mass_from == "--mass") continue;
    result.computed->mass *= factor;
    result.computed->inertia *= factor;
    result.mass_from = "--total-mass";
    result.mass_from_density = false;
  }
}

}  // namespace tumble::app::robot
