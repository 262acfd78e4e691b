#pragma once
/// @file A link's inertial from its geometry: each geometry's exact mass properties (meshes
/// through the same checks as `tumble inspect`, primitives in closed form), placed by its pose
/// and summed about their common centre of mass.

#include <optional>
#include <string>
#include <vector>

#include "app/robot/robot_model.hpp"
#include "engine/mass/inertia_method.hpp"
#include "engine/mass/mass_properties.hpp"
#include "engine/mass/mesh_analysis.hpp"

namespace tumble::app::robot {

struct ComputeOptions {
  /// kg/m^3. Unset: the link keeps the mass the file states (its weighed mass) and only the
  /// centre of mass and inertia follow from the shape; a link stating none gets 1000 kg/m^3
  /// (water; MuJoCo's default too). MJCF geoms with their own density or mass keep them
  /// relative to each other either way.
  std::optional<double> density;
  /// Overlapping parts within one mesh: their union (default), sum or an error (as `inspect
  /// --overlap`).
  engine::OverlapMode overlap = engine::OverlapMode::kUnion;
  /// How meshes become inertia (`--inertia`); an MJCF mesh's own method overrides it.
  engine::InertiaMethod inertia = engine::InertiaMethod::exact;
  /// m, for the shell method (`--shell T`). Unset, a shell's density is taken per area
  /// (kg/m^2), as MuJoCo's shellinertia reads it.
  std::optional<double> shell_thickness;
};

/// The method options one mesh geometry is computed with.
struct MeshMethod {
  engine::InertiaMethod inertia = engine::InertiaMethod::exact;
  std::optional<double> shell_thickness;
};

/// What came of one link.
struct LinkInertial {
  /// In the link's frame; unset when the link has no geometry (it keeps its inertial) or a
  /// geometry failed (`error`).
  std::optional<engine::MassProperties> computed;
  /// One line naming the link, the geometry and the file: "link 'arm' collision 0: arm.stl:
  /// has 12 boundary edges ...".
  std::optional<std::string> error;
  /// True when the mass came from a density rather than from the file.
  bool mass_from_density = false;
  /// Warnings of the meshes' checks and notes on the link, one sentence each.
  std::vector<std::string> notes;
  /// How each geometry's inertia was computed, in order: "exact", "convex", "shell" (meshes)
  /// or "primitive" (closed forms).
  std::vector<std::string> methods;
};

/// The distinct entries of `methods`, in order of first use, joined by ", " ("exact",
/// "convex, primitive"); "none" when empty.
std::string methods_text(const std::vector<std::string>& methods);

/// The mass properties of one geometry filled with `density`, in the link's frame (or, when
/// the geometry states its own mass, of that mass). Throws InputError naming the geometry.
/// `method` says how a mesh becomes inertia (the geometry's own MJCF method overrides it);
/// `used`, when given, receives the method's name ("exact", "convex", "shell", "primitive").
engine::MassProperties geometry_mass_properties(const Geometry& geometry, double density,
                                                engine::OverlapMode overlap,
                                                std::vector<std::string>* notes = nullptr,
                                                const MeshMethod& method = {},
                                                std::string* used = nullptr);

/// The link's inertial from its geometries (never throws InputError: failures are `error`).
LinkInertial compute_link_inertial(const Link& link, const ComputeOptions& options);

}  // namespace tumble::app::robot
