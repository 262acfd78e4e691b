// tumble.inspect, tumble.mass_properties, tumble.primitive and the MassProperties they return:
// the same calls `tumble inspect` makes (app/scene/mesh_inspection.hpp, engine/mass), with
// numpy in and out.
#include <pybind11/stl.h>

#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <variant>

#include "app/robot/inertial_xml.hpp"
#include "app/scene/mesh_inspection.hpp"
#include "app/scene/unit_hint.hpp"
#include "engine/mass/mesh_analysis.hpp"
#include "engine/mass/primitive_shapes.hpp"
#include "json_python.hpp"
#include "mass_bindings.hpp"
#include "python_support.hpp"

namespace tumble::python {
namespace {

/// How the mass properties were computed, as every output names it.
std::string method_of(const engine::MeshReport& report) {
  return engine::inertia_method_name(report.method);
}

/// The options every mass call shares, as the command line's flags give them.
engine::MassOptions mass_options(const std::optional<double>& density,
                                 const std::optional<double>& mass, const py::object& scale,
                                 const std::optional<double>& shell, const std::string& inertia,
                                 engine::OverlapMode overlap) {
  const std::optional<engine::InertiaMethod> method = engine::parse_inertia_method(inertia);
  if (!method) {
    throw_input_error("inertia: expected 'exact', 'convex', 'shell', 'legacy' or 'auto', got '" +
                      inertia + "'");
  }
  if (*method == engine::InertiaMethod::shell && !shell && !mass) {
    throw_input_error("inertia: 'shell' needs shell=THICKNESS (metres) or mass=M (kg)");
  }
  if (density && mass) throw_input_error("density: give either a density or a mass, not both");
  engine::MassOptions options;
  options.density = density;
  options.mass = mass;
  options.shell_thickness = shell;
  options.inertia = *method;
  options.overlap = overlap;
  if (py::isinstance<py::float_>(scale) || py::isinstance<py::int_>(scale)) {
    options.scale = Eigen::Vector3d::Constant(scale.cast<double>());
  } else {
    options.scale = vector3(scale, "scale");
  }
  return options;
}

/// The triangle mesh of numpy arrays, checked: vertices (N, 3) finite numbers, faces (M, 3)
/// integers indexing them.
engine::TriangleMesh mesh_of_arrays(const py::handle& vertices, const py::handle& faces) {
  const py::array vertex_array = py::array::ensure(vertices);
  const py::array face_array = py::array::ensure(faces);
  if (!vertex_array || vertex_array.ndim() != 2 || vertex_array.shape(1) != 3) {
    throw_input_error("vertices: expected an array of shape (N, 3)");
  }
  if (!face_array || face_array.ndim() != 2 || face_array.shape(1) != 3) {
    throw_input_error("faces: expected an array of shape (M, 3)");
  }
  const char kind = face_array.dtype().kind();
  if (kind != 'i' && kind != 'u') {
    throw_input_error("faces: expected integer vertex indices, got an array of dtype " +
                      std::string(py::str(face_array.dtype())));
  }
  const auto points =
      py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(vertex_array);
  const auto indices =
      py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(face_array);
  if (!points) throw_input_error("vertices: expected numbers");
  engine::TriangleMesh mesh;
  const py::ssize_t n = points.shape(0);
  const auto p = points.unchecked<2>();
  mesh.positions.resize(static_cast<std::size_t>(n));
  for (py::ssize_t i = 0; i < n; ++i) {
    mesh.positions[static_cast<std::size_t>(i)] = Eigen::Vector3d(p(i, 0), p(i, 1), p(i, 2));
    if (!mesh.positions[static_cast<std::size_t>(i)].allFinite()) {
      throw_input_error("vertices[" + std::to_string(i) + "]: not a finite point");
    }
  }
  const auto f = indices.unchecked<2>();
  mesh.triangles.resize(static_cast<std::size_t>(f.shape(0)));
  for (py::ssize_t t = 0; t < f.shape(0); ++t) {
    for (py::ssize_t c = 0; c < 3; ++c) {
      const std::int64_t v = f(t, c);
      if (v < 0 || v >= n) {
        throw_input_error("faces[" + std::to_string(t) + "]: vertex index " + std::to_string(v) +
                          " out of range (" + std::to_string(n) + " vertices, indices from 0)");
      }
      mesh.triangles[static_cast<std::size_t>(t)][static_cast<std::size_t>(c)] =
          static_cast<std::uint32_t>(v);
    }
  }
  if (mesh.triangles.empty()) throw_input_error("faces: no triangles");
  return mesh;
}

/// A primitive's dimensions from keyword arguments (metres).
engine::Shape shape_of(const std::string& kind, const py::kwargs& dimensions) {
  const auto number = [&](const char* name) {
    if (!dimensions.contains(name)) throw_input_error(kind + ": missing dimension '" + name + "'");
    return dimensions[name].cast<double>();
  };
  const auto triple = [&](const char* name) {
    if (!dimensions.contains(name)) throw_input_error(kind + ": missing dimension '" + name + "'");
    return vector3(dimensions[name], kind + " " + name);
  };
  engine::Shape shape;
  std::vector<std::string> names;
  if (kind == "box") {
    shape = engine::Box{triple("size")}, names = {"size"};
  } else if (kind == "sphere") {
    shape = engine::Sphere{number("radius")}, names = {"radius"};
  } else if (kind == "cylinder") {
    shape = engine::Cylinder{number("radius"), number("length")}, names = {"radius", "length"};
  } else if (kind == "capsule") {
    shape = engine::Capsule{number("radius"), number("length")}, names = {"radius", "length"};
  } else if (kind == "ellipsoid") {
    shape = engine::Ellipsoid{triple("radii")}, names = {"radii"};
  } else if (kind == "cone") {
    shape = engine::Cone{number("radius"), number("height")}, names = {"radius", "height"};
  } else {
    throw_input_error("kind: expected box, sphere, cylinder, capsule, ellipsoid or cone, got '" +
                      kind + "'");
  }
  for (const auto& item : dimensions) {
    const std::string name = py::str(item.first);
    if (std::find(names.begin(), names.end(), name) == names.end()) {
      throw_input_error(kind + ": unknown dimension '" + name + "'");
    }
  }
  return shape;
}

/// Half the extent of a primitive along x, y, z (its bounds are +- this, but the cone's).
std::pair<Eigen::Vector3d, Eigen::Vector3d> shape_bounds(const engine::Shape& shape) {
  return std::visit(
      [](const auto& s) -> std::pair<Eigen::Vector3d, Eigen::Vector3d> {
        using S = std::decay_t<decltype(s)>;
        Eigen::Vector3d half;
        if constexpr (std::is_same_v<S, engine::Box>) half = 0.5 * s.size;
        if constexpr (std::is_same_v<S, engine::Sphere>) half.setConstant(s.radius);
        if constexpr (std::is_same_v<S, engine::Cylinder>)
          half = {s.radius, s.radius, 0.5 * s.length};
        if constexpr (std::is_same_v<S, engine::Capsule>) {
          half = {s.radius, s.radius, 0.5 * s.length + s.radius};
        }
        if constexpr (std::is_same_v<S, engine::Ellipsoid>) half = s.radii;
        if constexpr (std::is_same_v<S, engine::Cone>) {
          return {{-s.radius, -s.radius, -0.25 * s.height}, {s.radius, s.radius, 0.75 * s.height}};
        }
        return {-half, half};
      },
      shape);
}

}  // namespace

MassPropertiesResult::MassPropertiesResult(engine::MeshReport mesh)
    : report(std::move(mesh)),
      method(method_of(*report)),
      dictionary(app::report_to_json(*report)) {
  dictionary["method"] = method;
}

MassPropertiesResult::MassPropertiesResult(const engine::Shape& shape,
                                           const engine::MassProperties& properties) {
  engine::MeshReport made;
  made.source = std::string(engine::shape_kind(shape));
  made.volume = engine::volume(shape);
  made.density = properties.mass / made.volume;
  made.mass_properties = properties;
  made.principal = engine::principal_frame(properties.inertia);
  std::tie(made.bounds_min, made.bounds_max) = shape_bounds(shape);
  report = std::move(made);
  method = "closed form";
  const engine::MassProperties& mp = report->mass_properties;
  dictionary = {
      {"kind", report->source},
      {"volume", report->volume},
      {"mass", mp.mass},
      {"density", report->density},
      {"center_of_mass", {mp.center_of_mass.x(), mp.center_of_mass.y(), mp.center_of_mass.z()}},
      {"method", method},
  };
  const nlohmann::json mesh_like = app::report_to_json(*report);
  for (const char* key : {"inertia", "principal_moments", "principal_axes", "bounds", "warnings"}) {
    dictionary[key] = mesh_like[key];
  }
}

namespace {

/// MassProperties.to_xml: the inertial element `tumble inspect --format FORMAT` prints.
std::string inertial_xml(const MassPropertiesResult& r, const std::string& format,
                         const std::string& frame) {
  app::robot::RobotFormat robot_format{};
  if (format == "urdf") {
    robot_format = app::robot::RobotFormat::urdf;
  } else if (format == "sdf") {
    robot_format = app::robot::RobotFormat::sdf;
  } else if (format == "mjcf") {
    robot_format = app::robot::RobotFormat::mjcf;
  } else {
    throw_input_error("format: expected urdf, sdf or mjcf, got '" + format + "'");
  }
  if (frame != "mesh" && frame != "principal") {
    throw_input_error("frame: expected mesh or principal, got '" + frame + "'");
  }
  return app::robot::inertial_element(
      robot_format, r.report->mass_properties,
      frame == "mesh" ? app::robot::InertialFrame::mesh : app::robot::InertialFrame::principal);
}

MassPropertiesResult inspect_path(const std::string& path, const engine::MassOptions& options) {
  py::gil_scoped_release release;
  engine::MeshReport report =
      naming_files({path}, [&] { return app::inspect_file(path, options); });
  if (auto hint = app::unit_hint(report, options.scale))
    report.warnings.push_back(std::move(*hint));
  return MassPropertiesResult(std::move(report));
}

/// tumble.MassProperties.
void bind_mass_properties_class(py::module_& module) {
  py::class_<MassPropertiesResult> result(module, "MassProperties", R"doc(
Mass properties of one body, in SI units (metres, kilograms), in the mesh file's axes after
`scale`.

volume (m^3), mass (kg), density (kg/m^3), center_of_mass (3,) m, inertia (3, 3) kg m^2 about
the centre of mass, principal_moments (3,) ascending, principal_axes (3, 3) whose COLUMNS are
the principal axes (inertia = axes @ diag(moments) @ axes.T, det = +1),
principal_quaternion (w, x, y, z) of that rotation, bounds ((3,), (3,)) the corners of the
axis-aligned box, warnings (list of str, never dropped), method ("exact", "shell",
"closed form"). to_dict() is the object `tumble inspect --json` prints for the same file.
)doc");
  result.attr("__module__") = "tumble";
  result
      .def_property_readonly("volume",
                             [](const MassPropertiesResult& r) { return r.report->volume; })
      .def_property_readonly(
          "mass", [](const MassPropertiesResult& r) { return r.report->mass_properties.mass; })
      .def_property_readonly("density",
                             [](const MassPropertiesResult& r) { return r.report->density; })
      .def_property_readonly("center_of_mass",
                             [](const MassPropertiesResult& r) {
                               return to_numpy(r.report->mass_properties.center_of_mass);
                             })
      .def_property_readonly(
          "inertia",
          [](const MassPropertiesResult& r) { return to_numpy(r.report->mass_properties.inertia); })
      .def_property_readonly(
          "principal_moments",
          [](const MassPropertiesResult& r) { return to_numpy(r.report->principal.moments); })
      .def_property_readonly(
          "principal_axes",
          [](const MassPropertiesResult& r) { return to_numpy(r.report->principal.axes); })
      .def_property_readonly("principal_quaternion",
                             [](const MassPropertiesResult& r) {
                               const Eigen::Quaterniond q(r.report->principal.axes);
                               py::array_t<double> out(4);
                               auto view = out.mutable_unchecked<1>();
                               view(0) = q.w(), view(1) = q.x(), view(2) = q.y(), view(3) = q.z();
                               return out;
                             })
      .def_property_readonly("bounds",
                             [](const MassPropertiesResult& r) {
                               return py::make_tuple(to_numpy(r.report->bounds_min),
                                                     to_numpy(r.report->bounds_max));
                             })
      .def_property_readonly("warnings",
                             [](const MassPropertiesResult& r) { return r.report->warnings; })
      .def_property_readonly("method", [](const MassPropertiesResult& r) { return r.method; })
      .def_property_readonly("source",
                             [](const MassPropertiesResult& r) { return r.report->source; })
      .def(
          "inertia_about",
          [](const MassPropertiesResult& r, const py::object& point) {
            return to_numpy(r.report->mass_properties.inertia_about(vector3(point, "point")));
          },
          py::arg("point"),
          "The inertia tensor (3, 3), kg m^2, about `point` (3,) m, same axes (parallel axes).")
      .def(
          "to_dict", [](const MassPropertiesResult& r) { return json_to_python(r.dictionary); },
          "A dict equal to the JSON object `tumble inspect --json` prints for the same file.")
      .def("to_xml", &inertial_xml, py::arg("format"), py::arg("frame") = "mesh",
           "The inertial element `tumble inspect --format FORMAT --frame FRAME` prints: FORMAT "
           "urdf, sdf or mjcf; FRAME mesh (the file's axes, all six elements) or principal.")
      .def("__repr__", [](const MassPropertiesResult& r) {
        return "<tumble.MassProperties of " + r.report->source + ": mass " +
               std::to_string(r.report->mass_properties.mass) + " kg, " + r.method + ">";
      });
}

/// tumble.inspect, tumble.mass_properties and tumble.primitive.
void bind_mass_functions(py::module_& module) {
  module.def(
      "inspect",
      [](const py::object& path, std::optional<double> density, std::optional<double> mass,
         const py::object& scale, std::optional<double> shell, const std::string& inertia,
         const std::optional<std::string>& overlap, bool allow_overlap) {
        const std::string file = py::str(py::module_::import("os").attr("fspath")(path));
        return inspect_path(file, mass_options(density, mass, scale, shell, inertia,
                                               overlap_mode_of(overlap, allow_overlap)));
      },
      py::arg("path"), py::kw_only(), py::arg("density") = py::none(), py::arg("mass") = py::none(),
      py::arg("scale") = 1.0, py::arg("shell") = py::none(), py::arg("inertia") = "exact",
      py::arg("overlap") = py::none(), py::arg("allow_overlap") = false,
      R"doc(Mass properties of one mesh file, as `tumble inspect FILE` computes them.

density: kg/m^3 (default 1000, water); mass: kg, total (excludes density); scale: file units
to metres, one factor or (sx, sy, sz) (0.001 for millimetres); shell: thickness in metres for
a thin shell of the surface; inertia: "exact" (a closed mesh), "convex" (the convex hull's
solid), "shell" (with shell= or mass=) or "auto" (exact, else convex with a warning); the
result's method says which was used; overlap: parts that overlap, nest facing the same way or
repeat are "union" (their exact union, the default; a warning states the shared volume), "sum"
(each counted whole) or "refuse" (an error), as --overlap; allow_overlap=True: the same as
overlap="sum".
Raises tumble.InputError (a ValueError) with the command line's one-line message.)doc");

  module.def(
      "mass_properties",
      [](const py::object& vertices, const py::object& faces, std::optional<double> density,
         std::optional<double> mass, const py::object& scale, std::optional<double> shell,
         const std::string& inertia, const std::optional<std::string>& overlap,
         bool allow_overlap) {
        const engine::MassOptions options = mass_options(density, mass, scale, shell, inertia,
                                                         overlap_mode_of(overlap, allow_overlap));
        engine::TriangleMesh mesh = mesh_of_arrays(vertices, faces);
        py::gil_scoped_release release;
        return MassPropertiesResult(engine::analyze_mesh(std::move(mesh), options, "mesh arrays"));
      },
      py::arg("vertices"), py::arg("faces"), py::kw_only(), py::arg("density") = py::none(),
      py::arg("mass") = py::none(), py::arg("scale") = 1.0, py::arg("shell") = py::none(),
      py::arg("inertia") = "exact", py::arg("overlap") = py::none(),
      py::arg("allow_overlap") = false,
      R"doc(Mass properties of a triangle mesh given as numpy arrays, with the checks a file gets
(open, flipped, self-intersecting or overlapping parts...).

vertices: (N, 3) float, metres (before `scale`); faces: (M, 3) integer indices into vertices,
wound outward (counter-clockwise seen from outside). Other options as tumble.inspect.)doc");

  module.def(
      "primitive",
      [](const std::string& kind, std::optional<double> density, std::optional<double> mass,
         const py::kwargs& dimensions) {
        const engine::Shape shape = shape_of(kind, dimensions);
        if (density && mass)
          throw_input_error(kind + ": give either a density or a mass, not both");
        const engine::MassProperties properties =
            mass ? engine::mass_properties_of_mass(shape, *mass)
                 : engine::mass_properties(shape, density.value_or(1000.0));
        return MassPropertiesResult(shape, properties);
      },
      py::arg("kind"), py::kw_only(), py::arg("density") = py::none(), py::arg("mass") = py::none(),
      R"doc(Exact mass properties of a primitive solid, centred at the origin, axis along z.

kind and its dimensions (metres): box(size=(x, y, z)), sphere(radius), cylinder(radius,
length), capsule(radius, length of the cylindrical part), ellipsoid(radii=(a, b, c)),
cone(radius, height; base at z = -height/4). density kg/m^3 (default 1000) or mass kg.)doc");
}

}  // namespace

void bind_mass(py::module_& module) {
  bind_mass_properties_class(module);
  bind_mass_functions(module);
}

}  // namespace tumble::python
