// One mesh file's mass properties and checks, as `tumble inspect`, scenes and the viewer's
// inspector report them.
#include "app/scene/mesh_inspection.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "engine/import/mesh_import.hpp"

namespace tumble::app {
namespace {

nlohmann::json vector_json(const Eigen::Vector3d& v) {
  return {v.x(), v.y(), v.z()};
}

nlohmann::json matrix_json(const Eigen::Matrix3d& m) {
  nlohmann::json rows = nlohmann::json::array();
  for (int r = 0; r < 3; ++r) rows.push_back({m(r, 0), m(r, 1), m(r, 2)});
  return rows;
}

std::string fixed(const char* format, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

/// Three aligned numbers, 7 significant digits; entries below 1e-12 of `scale` are rounding
/// noise of an exact zero and print as 0 (the JSON report keeps every digit).
std::string vector_text(const Eigen::Vector3d& v, double scale) {
  std::string out = "[";
  for (int i = 0; i < 3; ++i) {
    const double value = std::abs(v[i]) < 1e-12 * scale ? 0.0 : v[i];
    out += fixed(" %14.7g", value);
  }
  return out + " ]";
}

std::string with_thousands(std::size_t value) {
  const std::string digits = std::to_string(value);
  std::string out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

/// The method that gave the numbers, and why when exact was refused.
std::string method_text(const engine::MeshReport& report) {
  switch (report.method) {
    case engine::InertiaMethod::convex:
      return report.fallback_reason ? "convex (hull's solid; exact refused the mesh)"
                                    : "convex (the convex hull's solid)";
    case engine::InertiaMethod::shell:
      return "shell (the surface, uniform areal density)";
    case engine::InertiaMethod::legacy:
      return "legacy (MuJoCo's approximation)";
    default:
      return "exact (the enclosed solid)";
  }
}

}  // namespace

engine::MeshReport inspect_file(const std::filesystem::path& file, const engine::MassOptions& mass,
                                engine::TriangleMesh* imported) {
  engine::ImportStats stats;
  engine::TriangleMesh mesh = engine::import_mesh(file, &stats);
  if (imported != nullptr) *imported = mesh;
  engine::MeshReport report =
      engine::analyze_mesh(std::move(mesh), mass, file.string(), stats.distinct_positions);
  report.welded_vertices += stats.welded_vertices;
  // What the import skipped (faces of one or two corners) is said with the checks.
  report.warnings.insert(report.warnings.end(), stats.warnings.begin(), stats.warnings.end());
  return report;
}

nlohmann::json report_to_json(const engine::MeshReport& report) {
  const engine::MassProperties& mp = report.mass_properties;
  nlohmann::json out = {
      {"file", report.source},
      {"triangles", report.triangles},
      {"input_triangles", report.input_triangles},
      {"degenerate_triangles", report.degenerate_triangles},
      {"vertices", report.vertices},
      {"welded_vertices", report.welded_vertices},
      {"parts", report.parts},
      {"cavities", report.cavities},
      {"watertight", report.watertight},
      {"boundary_edges", report.boundary_edges},
      {"inconsistent_edges", report.inconsistent_edges},
      {"non_manifold_edges", report.non_manifold_edges},
      {"flipped", report.flipped},
      {"shell", report.shell},
      {"method", engine::inertia_method_name(report.method)},
      {"volume", report.volume},
      {"mass", mp.mass},
      {"density", report.density},
      {"center_of_mass", vector_json(mp.center_of_mass)},
      {"inertia", matrix_json(mp.inertia)},
      {"principal_moments", vector_json(report.principal.moments)},
      {"principal_axes", matrix_json(report.principal.axes)},
      {"bounds", {vector_json(report.bounds_min), vector_json(report.bounds_max)}},
      {"warnings", report.warnings},
  };
  if (report.shell) {
    out["thickness"] = report.thickness;
    out["area"] = report.area;
    out["areal_density"] = report.areal_density;
  } else {
    // How overlapping parts were counted (--overlap), and what their union took out.
    out["overlap"] = engine::overlap_mode_name(report.overlap);
    out["united_parts"] = report.united_parts;
    out["shared_volume"] = report.shared_volume;
  }
  if (report.method == engine::InertiaMethod::convex) {
    out["hull_volume"] = report.hull_volume;
    out["hull_triangles"] = report.hull_triangles;
  }
  if (report.method == engine::InertiaMethod::convex ||
      report.method == engine::InertiaMethod::legacy) {
    out["enclosed_volume"] =
        report.enclosed_volume ? nlohmann::json(*report.enclosed_volume) : nlohmann::json(nullptr);
  }
  if (report.fallback_reason) out["exact_refused"] = *report.fallback_reason;
  return out;
}

std::string format_report(const engine::MeshReport& report) {
  const engine::MassProperties& mp = report.mass_properties;
  std::ostringstream out;
  const auto row = [&](const std::string& label, const std::string& value) {
    out << "  " << label << std::string(label.size() < 18 ? 18 - label.size() : 1, ' ') << value
        << "\n";
  };
  out << report.source << (report.shell ? "  (thin shell)" : "") << "\n";
  row("inertia", method_text(report));
  row("triangles",
      with_thousands(report.triangles) + " in " + std::to_string(report.parts) +
          (report.parts == 1 ? " part" : " parts") +
          (report.cavities ? ", " + std::to_string(report.cavities) + " cavities" : ""));
  row("vertices", with_thousands(report.vertices) + " (" + with_thousands(report.welded_vertices) +
                      " duplicates welded)");
  const Eigen::Vector3d size = report.bounds_max - report.bounds_min;
  const double length = size.maxCoeff();
  const double moment = report.principal.moments.maxCoeff();
  row("size", vector_text(size, length) + " m");
  if (report.shell) {
    row("area", fixed("%.9g", report.area) + " m^2");
    if (report.thickness > 0.0) row("thickness", fixed("%.9g", report.thickness) + " m");
    row("areal density", fixed("%.9g", report.areal_density) + " kg/m^2");
  }
  if (report.method != engine::InertiaMethod::exact && !report.shell && report.enclosed_volume) {
    row("enclosed volume", fixed("%.9g", *report.enclosed_volume) + " m^3 (the mesh's own solid)");
  }
  if (!report.shell || report.thickness > 0.0) {
    row("volume", fixed("%.9g", report.volume) + " m^3");
    row("density", fixed("%.9g", report.density) + " kg/m^3");
  }
  if (!report.shell && (report.parts > 1 || report.united_parts > 0)) {
    row("overlap",
        std::string(engine::overlap_mode_name(report.overlap)) +
            (report.united_parts > 0
                 ? " of " + std::to_string(report.united_parts) + " parts, shared volume " +
                       fixed("%.9g", report.shared_volume) + " m^3 counted once"
                 : ""));
  }
  row("mass", fixed("%.9g", mp.mass) + " kg");
  row("centre of mass", vector_text(mp.center_of_mass, length) + " m");
  out << "  inertia about the centre of mass, file axes (kg m^2)\n";
  for (int r = 0; r < 3; ++r) {
    out << "                    " << vector_text(mp.inertia.row(r), moment) << "\n";
  }
  row("principal moments",
      vector_text(report.principal.moments, moment) + " kg m^2 (I1 <= I2 <= I3)");
  out << "  principal axes (columns; a rotation from principal to file axes)\n";
  for (int r = 0; r < 3; ++r) {
    out << "                    " << vector_text(report.principal.axes.row(r), 1.0) << "\n";
  }
  out << "  checks\n";
  const auto check = [&](bool ok, const std::string& text) {
    out << "    " << (ok ? "ok    " : "warn  ") << text << "\n";
  };
  if (report.method == engine::InertiaMethod::convex) {
    check(report.boundary_edges == 0,
          "convex hull of the vertices: closure and winding not required (" +
              with_thousands(report.boundary_edges) + " boundary edges)");
  } else if (report.method == engine::InertiaMethod::legacy) {
    check(report.boundary_edges == 0,
          "MuJoCo's legacy approximation: closure and winding not required (" +
              with_thousands(report.boundary_edges) + " boundary edges)");
  } else if (!report.shell) {
    check(true, "closed surface (0 boundary edges)");
    check(true, "consistent winding");
    check(!report.flipped,
          report.flipped ? "faces pointed inward: flipped" : "faces point outward");
  } else {
    check(true, "thin shell: closure and winding not required (" +
                    with_thousands(report.boundary_edges) + " boundary edges)");
  }
  check(report.degenerate_triangles == 0,
        with_thousands(report.degenerate_triangles) + " degenerate triangles skipped");
  check(true, "principal moments positive and satisfy the triangle inequality");
  for (const std::string& warning : report.warnings) out << "    note  " << warning << "\n";
  return out.str();
}

}  // namespace tumble::app
