// A link's inertial from its geometry.
#include "app/robot/link_inertial.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <type_traits>

#include "app/scene/mesh_inspection.hpp"
#include "app/scene/unit_hint.hpp"
#include "base/errors.hpp"
#include "engine/mass/mesh_analysis.hpp"

namespace tumble::app::robot {
namespace {

constexpr double kDefaultDensity = 1000.0;  // kg/m^3, water

/// A shell with no thickness takes the density per area: a nominal thickness of 1 m.
constexpr double kAreaDensityThickness = 1.0;

/// The scale a robot file of `format` gives a mesh, `factor` on every axis.
std::string scale_attribute(RobotFormat format, double factor) {
  char number[32];
  std::snprintf(number, sizeof number, "%g", factor);
  const std::string f = number;
  const std::string three = f + " " + f + " " + f;
  switch (format) {
    case RobotFormat::urdf:
      return "add scale=\"" + three + "\" to the <mesh>";
    case RobotFormat::sdf:
      return "add <scale>" + three + "</scale> to the <mesh>";
    case RobotFormat::mjcf:
      return "add scale=\"" + three + "\" to the asset's <mesh>";
  }
  return "";
}

engine::MassProperties mesh_properties(const MeshGeometry& mesh, double density,
                                       std::optional<double> mass, engine::OverlapMode overlap,
                                       std::vector<std::string>* notes, const MeshMethod& method,
                                       std::string* used) {
  engine::MassOptions options;
  if (mass) {
    options.mass = mass;
  } else {
    options.density = density;
  }
  options.scale = mesh.scale;
  options.overlap = overlap;
  options.inertia = mesh.inertia.value_or(method.inertia);
  if (options.inertia == engine::InertiaMethod::shell) {
    options.shell_thickness =
        mesh.inertia ? std::optional<double>(kAreaDensityThickness) : method.shell_thickness;
    if (!options.shell_thickness && !mass) options.shell_thickness = kAreaDensityThickness;
  }
  const engine::MeshReport report = inspect_file(mesh.file, options);
  if (notes) {
    for (const std::string& warning : report.warnings) {
      notes->push_back(mesh.file.string() + ": " + warning);
    }
    if (const auto factor = likely_unit_factor(report, mesh.scale); factor && method.hint_format) {
      char size[32];
      std::snprintf(size, sizeof size, "%.4g", (report.bounds_max - report.bounds_min).maxCoeff());
      notes->push_back(mesh.file.string() + ": size " + size + " m: is the file in " +
                       unit_name(*factor) + "? " + scale_attribute(*method.hint_format, *factor));
    }
    if (mesh.inertia) {
      notes->push_back(mesh.file.string() + ": inertia method " +
                       engine::inertia_method_name(*mesh.inertia) + " as the file asks");
    }
  }
  if (used) *used = engine::inertia_method_name(report.method);
  return report.mass_properties;
}

}  // namespace

std::string methods_text(const std::vector<std::string>& methods) {
  std::vector<std::string> distinct;
  std::string out;
  for (const std::string& method : methods) {
    if (std::find(distinct.begin(), distinct.end(), method) != distinct.end()) continue;
    out += (distinct.empty() ? "" : ", ") + method;
    distinct.push_back(method);
  }
  return distinct.empty() ? "none" : out;
}

engine::MassProperties geometry_mass_properties(const Geometry& geometry, double density,
                                                engine::OverlapMode overlap,
                                                std::vector<std::string>* notes,
                                                const MeshMethod& method, std::string* used) {
  const double rho = geometry.density.value_or(density);
  engine::MassProperties local;
  try {
    local = std::visit(
        [&](const auto& shape) {
          using T = std::decay_t<decltype(shape)>;
          if constexpr (std::is_same_v<T, MeshGeometry>) {
            return mesh_properties(shape, rho, geometry.mass, overlap, notes, method, used);
          } else {
            if (used) *used = "primitive";
            return geometry.mass ? engine::mass_properties_of_mass(shape, *geometry.mass)
                                 : engine::mass_properties(shape, rho);
          }
        },
        geometry.shape);
  } catch (const InputError& error) {
    throw InputError(geometry.where + ": " + error.what());
  }
  return local.rotated(geometry.pose.linear()).translated(geometry.pose.translation());
}

namespace {

/// The note on a link whose mass came from densities without --density: which were used.
std::string density_note(const Link& link) {
  if (link.auto_inertial) return "";
  const auto own = [](const Geometry& g) { return g.density || g.mass; };
  const bool all_own = std::all_of(link.geometries.begin(), link.geometries.end(), own);
  const bool some_own = std::any_of(link.geometries.begin(), link.geometries.end(), own);
  const std::string why = "states no usable mass (none, zero or negative): ";
  return why + (all_own    ? "computed from its geometries' own densities and masses"
                : some_own ? "computed from its geometries' own densities and masses, "
                             "1000 kg/m^3 where one gives none (give --density)"
                           : "filled with 1000 kg/m^3 (give --density)");
}

}  // namespace

LinkInertial compute_link_inertial(const Link& link, const ComputeOptions& options,
                                   RobotFormat format) {
  LinkInertial out;
  if (link.geometries.empty()) {
    out.notes.push_back(link.stated ? "no geometry: its inertial is kept as the file states it"
                                    : "no geometry and no inertial: nothing to compute");
    return out;
  }
  // The file's mass, when it is one (zero, negative or missing masses are flagged elsewhere).
  double stated_mass = 0.0;
  if (link.stated && link.stated->mass) stated_mass = *link.stated->mass;
  const std::optional<double> link_density = value_for(options.link_densities, link.name);
  const std::optional<double> weighed = value_for(options.link_masses, link.name);
  const bool some_density = options.density || link_density || options.total_mass;
  const bool keep_mass =
      !some_density && !weighed && stated_mass > 0.0 && std::isfinite(stated_mass);
  const double density = options.density.value_or(kDefaultDensity);
  std::vector<engine::MassProperties> parts;
  const MeshMethod method{options.inertia, options.shell_thickness, format};
  try {
    for (Geometry geometry : link.geometries) {
      // --density LINK=RHO wins over the geometry's own density or mass.
      if (link_density) {
        geometry.density = link_density;
        geometry.mass.reset();
      }
      std::string used;
      parts.push_back(
          geometry_mass_properties(geometry, density, options.overlap, &out.notes, method, &used));
      out.methods.push_back(used);
    }
  } catch (const InputError& error) {
    out.error = error.what();
    return out;
  }
  engine::MassProperties total = engine::combined(parts);
  out.mass_from = keep_mass ? "stated" : weighed ? "--mass" : "density";
  out.mass_from_density = out.mass_from == "density";
  if (keep_mass || weighed) {
    const double mass = weighed ? *weighed : stated_mass;
    total.inertia *= mass / total.mass;
    total.mass = mass;
  } else if (!some_density) {
    if (const std::string note = density_note(link); !note.empty()) out.notes.push_back(note);
  }
  out.computed = total;
  return out;
}

}  // namespace tumble::app::robot
