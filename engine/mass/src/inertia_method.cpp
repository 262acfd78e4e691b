// Names of the inertia methods, as the command line, scenes and reports spell them.
#include "engine/mass/inertia_method.hpp"

namespace tumble::engine {

std::string inertia_method_name(InertiaMethod method) {
  switch (method) {
    case InertiaMethod::exact:
      return "exact";
    case InertiaMethod::convex:
      return "convex";
    case InertiaMethod::shell:
      return "shell";
    case InertiaMethod::legacy:
      return "legacy";
    case InertiaMethod::automatic:
      return "auto";
  }
  return "exact";
}

std::optional<InertiaMethod> parse_inertia_method(const std::string& name) {
  if (name == "exact") return InertiaMethod::exact;
  if (name == "convex") return InertiaMethod::convex;
  if (name == "shell") return InertiaMethod::shell;
  if (name == "legacy") return InertiaMethod::legacy;
  if (name == "auto") return InertiaMethod::automatic;
  return std::nullopt;
}

}  // namespace tumble::engine
