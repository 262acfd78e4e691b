// tumble.inertials and tumble.RobotInertials: the comparison `tumble inertials` makes
// (app/robot/inertials_report.hpp), its JSON as dicts, and the file rewritten by the command's
// own writer.
#include <pybind11/stl.h>

#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app/robot/inertials_report.hpp"
#include "json_python.hpp"
#include "python_support.hpp"
#include "robot_bindings.hpp"

namespace tumble::python {
namespace {

/// `tumble inertials --tolerance`'s default.
constexpr double kDefaultInertialsTolerance = 1e-3;

app::robot::PackagePaths package_paths_of(const py::dict& given) {
  app::robot::PackagePaths out;
  for (const auto& item : given) {
    const std::string name = py::str(item.first);
    const std::string folder = py::str(py::module_::import("os").attr("fspath")(item.second));
    if (name.empty() || folder.empty()) {
      throw_input_error("package_paths: expected {NAME: DIR}, got '" + name + "': '" + folder +
                        "'");
    }
    out.emplace_back(name, folder);
  }
  return out;
}

/// {LINK: value} of the keyword `name` as (link, positive value) pairs.
std::vector<std::pair<std::string, double>> link_values(const py::dict& values, const char* name) {
  std::vector<std::pair<std::string, double>> out;
  for (const auto& [key, value] : values) {
    const double number = py::cast<double>(value);
    if (!(number > 0.0 && std::isfinite(number))) {
      throw_input_error(std::string(name) + ": " + py::cast<std::string>(py::str(key)) +
                        ": expected a positive number");
    }
    out.emplace_back(py::cast<std::string>(py::str(key)), number);
  }
  return out;
}

/// The weighed masses and per-link densities of tumble.inertials.
struct WeighedOptions {
  py::dict densities;
  py::dict masses;
  std::optional<double> total_mass;
};

app::InertialsReport robot_inertials(const std::string& path, const std::string& geometry,
                                     std::optional<double> density, const py::dict& packages,
                                     engine::OverlapMode overlap, const std::string& inertia,
                                     const WeighedOptions& weighed) {
  app::robot::ReadOptions read;
  if (geometry == "collision") {
    read.from = app::robot::GeometrySource::collision;
  } else if (geometry == "visual") {
    read.from = app::robot::GeometrySource::visual;
  } else {
    throw_input_error("geometry: expected collision or visual, got '" + geometry + "'");
  }
  if (density && !(*density > 0.0 && std::isfinite(*density))) {
    throw_input_error("density: expected a positive number of kg/m^3");
  }
  read.packages = package_paths_of(packages);
  app::robot::ComputeOptions compute;
  compute.density = density;
  compute.link_densities = link_values(weighed.densities, "densities");
  compute.link_masses = link_values(weighed.masses, "masses");
  if (weighed.total_mass && !(*weighed.total_mass > 0.0 && std::isfinite(*weighed.total_mass))) {
    throw_input_error("total_mass: expected a positive number of kg");
  }
  compute.total_mass = weighed.total_mass;
  compute.overlap = overlap;
  const std::optional<engine::InertiaMethod> method = engine::parse_inertia_method(inertia);
  if (!method || *method == engine::InertiaMethod::shell) {
    throw_input_error("inertia: expected 'exact', 'convex' or 'auto', got '" + inertia + "'");
  }
  compute.inertia = *method;
  py::gil_scoped_release release;
  return naming_files({path}, [&] { return app::compute_inertials(path, read, compute); });
}

app::robot::InertialFrame frame_of(const std::string& frame) {
  if (frame == "mesh") return app::robot::InertialFrame::mesh;
  if (frame == "principal") return app::robot::InertialFrame::principal;
  throw_input_error("frame: expected mesh or principal, got '" + frame + "'");
}

std::vector<std::string> failing_links(const app::InertialsReport& report, double tolerance) {
  std::vector<std::string> names;
  for (const app::LinkComparison& link : report.links) {
    if (!app::within_tolerance(link, tolerance)) names.push_back(link.name);
  }
  return names;
}

void bind_robot_inertials_class(py::module_& module) {
  py::class_<app::InertialsReport> report(module, "RobotInertials", R"doc(
Each link's inertial of a robot file (URDF, SDF, MJCF) computed from its geometry and compared
with the one the file states, as `tumble inertials` reports it. SI units, each link's frame.

file, format ("urdf", "sdf", "mjcf"), geometry ("collision" or "visual"); links: one dict per
link in the file's order (name, stated, computed, differences, problems, notes: the objects of
`tumble inertials --json`); errors: one line per link whose geometry failed (then write()
refuses); failing(tolerance=1e-3): the names of the links `--check --tolerance` fails;
to_dict(tolerance=None): the object `tumble inertials --json` prints (with --check
--tolerance T when a tolerance is given); write(path, frame="mesh"): the file with the computed
inertials in place of the stated ones, every other byte kept.
)doc");
  report.attr("__module__") = "tumble";
  report
      .def_property_readonly("file",
                             [](const app::InertialsReport& r) { return r.robot.file.string(); })
      .def_property_readonly("format",
                             [](const app::InertialsReport& r) {
                               return app::comparison_to_json(r.robot, {}, r.source,
                                                              kDefaultInertialsTolerance,
                                                              false)["format"]
                                   .get<std::string>();
                             })
      .def_property_readonly("geometry", [](const app::InertialsReport& r) { return r.source; })
      .def_property_readonly(
          "links",
          [](const app::InertialsReport& r) {
            return json_to_python(app::comparison_to_json(
                r.robot, r.links, r.source, kDefaultInertialsTolerance, false)["links"]);
          })
      .def_property_readonly(
          "total",
          [](const app::InertialsReport& r) {
            return json_to_python(app::comparison_to_json(
                r.robot, {}, r.source, kDefaultInertialsTolerance, false, r.total)["total"]);
          })
      .def_property_readonly("errors", &app::InertialsReport::errors)
      .def("failing", &failing_links, py::arg("tolerance") = kDefaultInertialsTolerance,
           "Names of the links whose stated mass, centre of mass or inertia differ from the "
           "computed ones by more than `tolerance` (relative), state none, or are impossible.")
      .def(
          "to_dict",
          [](const app::InertialsReport& r, std::optional<double> tolerance) {
            return json_to_python(app::comparison_to_json(
                r.robot, r.links, r.source, tolerance.value_or(kDefaultInertialsTolerance),
                tolerance.has_value(), r.total));
          },
          py::arg("tolerance") = py::none())
      .def(
          "write",
          [](const app::InertialsReport& r, const py::object& path, const std::string& frame) {
            const std::string output = py::str(py::module_::import("os").attr("fspath")(path));
            const app::robot::InertialFrame chosen = frame_of(frame);
            py::gil_scoped_release release;
            app::write_inertials(r, output, chosen);
            return output;
          },
          py::arg("path"), py::kw_only(), py::arg("frame") = "mesh",
          "Writes the robot file with each computed inertial in place of the stated one (as "
          "`tumble inertials -o PATH --frame FRAME`; frame 'mesh' or 'principal'); atomically, "
          "never over the robot file itself. Returns the path.")
      .def("__repr__", [](const app::InertialsReport& r) {
        return "<tumble.RobotInertials " + r.robot.file.string() + ": " +
               std::to_string(r.links.size()) + " links>";
      });
}

}  // namespace

void bind_robot(py::module_& module) {
  bind_robot_inertials_class(module);
  module.def(
      "inertials",
      [](const py::object& robot, const std::string& geometry, std::optional<double> density,
         const py::dict& package_paths, const std::optional<std::string>& overlap,
         bool allow_overlap, const std::string& inertia, const py::dict& densities,
         const py::dict& masses, std::optional<double> total_mass) {
        const std::string path = py::str(py::module_::import("os").attr("fspath")(robot));
        return robot_inertials(path, geometry, density, package_paths,
                               overlap_mode_of(overlap, allow_overlap), inertia,
                               WeighedOptions{densities, masses, total_mass});
      },
      py::arg("robot"), py::kw_only(), py::arg("geometry") = "collision",
      py::arg("density") = py::none(), py::arg("package_paths") = py::dict(),
      py::arg("overlap") = py::none(), py::arg("allow_overlap") = false,
      py::arg("inertia") = "exact", py::arg("densities") = py::dict(),
      py::arg("masses") = py::dict(), py::arg("total_mass") = py::none(),
      R"doc(Each link's inertial of a robot file from its geometry, as `tumble inertials ROBOT`.

robot: a .urdf, .sdf/.world or MJCF .xml path; geometry: "collision" (default) or "visual"
(--from); density: kg/m^3 for every link (default: keep each link's stated mass, 1000 for a
link stating none); package_paths: {NAME: DIR} for package://NAME/ (--package-path NAME=DIR,
looked at before ROS_PACKAGE_PATH); overlap, allow_overlap: as inspect's; inertia: "exact",
"convex" or "auto" (--inertia; each link's computed["method"] names the one used); densities:
{LINK: kg/m^3} (--density LINK=RHO); masses: {LINK: kg} (--mass LINK=M); total_mass: kg
(--total-mass M); the report's `total` is the whole robot in its zero configuration. Returns
RobotInertials; a link whose geometry fails is in its errors (not raised); a bad file raises tumble.InputError.)doc");
}

}  // namespace tumble::python
