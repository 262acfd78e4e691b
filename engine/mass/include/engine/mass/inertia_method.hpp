#pragma once
/// @file How a mesh's geometry becomes a body's inertia: the exact solid it encloses, its convex
/// hull's solid, its surface as a thin shell, MuJoCo's legacy approximation, or exact with a
/// named fallback to the hull.

#include <optional>
#include <string>

namespace tumble::engine {

/// The inertia method asked for (`--inertia`, a scene's "inertia", MJCF's mesh inertia=).
enum class InertiaMethod {
  exact,      ///< the solid a closed, consistently wound surface encloses (refuses the rest)
  convex,     ///< the convex hull of the vertices as a solid (any mesh spanning a volume)
  shell,      ///< the surface as a thin shell of uniform areal density
  legacy,     ///< MuJoCo's approximation (its 2.2 default): absolute tetrahedra from the centre
  automatic,  ///< exact; where exact refuses, convex with a warning naming the reason
};

/// "exact", "convex", "shell", "legacy" or "auto".
std::string inertia_method_name(InertiaMethod method);

/// The method named `name` ("exact", "convex", "shell", "legacy", "auto"); nothing for any other
/// name.
std::optional<InertiaMethod> parse_inertia_method(const std::string& name);

}  // namespace tumble::engine
