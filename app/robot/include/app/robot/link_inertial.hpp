#pragma once
/// @file A link's inertial from its geometry: each geometry's exact mass properties (meshes
/// through the same checks as `tumble inspect`, primitives in closed form), placed by its pose
/// and summed about their common centre of mass.

#include <optional>
#include <string>
#include <utility>
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
  /// `--density LINK=RHO`: kg/m^3 for one link's geometries, over their own densities and
  /// masses (SDF collision density, MJCF geom density or mass) and over `density`.
  std::vector<std::pair<std::string, double>> link_densities;
  /// `--mass LINK=M`: a link's weighed mass (kg); its centre of mass and inertia follow from
  /// the geometry, the inertia scaled to this mass.
  std::vector<std::pair<std::string, double>> link_masses;
  /// `--total-mass M`: the whole robot's weighed mass (kg), spread by spread_total_mass over
  /// the links in proportion to their masses computed from densities.
  std::optional<double> total_mass;
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
  /// The robot file's format, to word the unit hint of a mesh whose size suggests another
  /// unit than metres (the scale attribute to add); unset: no hint.
  std::optional<RobotFormat> hint_format;
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
  /// Where the mass came from: "density", "stated" (the file's, kept), "--mass" or
  /// "--total-mass".
  std::string mass_from;
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
/// `format` words the unit hint of a mesh whose size suggests millimetres (its scale attribute).
LinkInertial compute_link_inertial(const Link& link, const ComputeOptions& options,
                                   RobotFormat format = RobotFormat::urdf);

/// The value `entries` gives for `name` (the last one given), or nothing.
std::optional<double> value_for(const std::vector<std::pair<std::string, double>>& entries,
                                const std::string& name);

/// Throws InputError "--density 'NAME=...': no link 'NAME' in FILE" (or --mass) when a
/// per-link option names no link of `robot`.
void check_link_options(const Robot& robot, const ComputeOptions& options);

/// Spreads `options.total_mass` over `results` (one per link of `links`, in order): links with
/// a --mass, and links without geometry that keep a stated mass, are subtracted first; the
/// rest is shared in proportion to the computed masses, each link's inertia scaled with its
/// mass. Nothing when total_mass is unset. Throws InputError "--total-mass M: ..." when the
/// fixed masses already reach it or no link is left to take the rest.
void spread_total_mass(const std::vector<Link>& links, std::vector<LinkInertial>& results,
                       const ComputeOptions& options);

}  // namespace tumble::app::robot
