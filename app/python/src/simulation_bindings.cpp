// tumble.simulate, the Trajectory it returns and tumble.integrators: the run `tumble simulate`
// makes (app/analysis/simulation_run.hpp), its recorded steps kept as numpy arrays, and the CSV
// written by the command's own writer.
//
// The run holds no GIL: the steps record into C++ vectors, and every 64 steps the stop check
// takes the GIL at most every 50 ms to run the interpreter's signal handlers (Ctrl-C).
#include <pybind11/stl.h>

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/analysis/simulation_run.hpp"
#include "engine/simulation/simulation.hpp"
#include "json_python.hpp"
#include "python_support.hpp"
#include "simulation_bindings.hpp"

namespace tumble::python {
namespace {

/// What tumble.Trajectory holds: the run's recorded trajectory (bodies, times, states,
/// summary), as the library returns it, with its numpy views.
struct TrajectoryResult : app::Trajectory {
  explicit TrajectoryResult(app::Trajectory run) : app::Trajectory(std::move(run)) {}

  /// A (N, B, width) array of `value(body, state)` over the recorded steps.
  template <int width, typename Value>
  py::array_t<double> per_body(Value&& value) const {
    const auto n = static_cast<py::ssize_t>(times.size());
    const auto b = static_cast<py::ssize_t>(bodies.size());
    std::vector<py::ssize_t> shape{n, b};
    if (width > 1) shape.push_back(width);
    py::array_t<double> out(shape);
    double* data = out.mutable_data();
    for (const auto& step : states) {
      for (std::size_t i = 0; i < bodies.size(); ++i) {
        const Eigen::Matrix<double, width, 1> v = value(bodies[i], step[i]);
        for (int c = 0; c < width; ++c) *data++ = v(c);
      }
    }
    return out;
  }
};

using Vector1d = Eigen::Matrix<double, 1, 1>;

/// The scene: a file's path, or a dict in the scene format (relative mesh paths from the
/// working directory; messages name it "<scene>").
app::SceneDescription scene_of(const py::object& scene) {
  if (py::isinstance<py::dict>(scene)) {
    const std::string text = py::str(py::module_::import("json").attr("dumps")(scene));
    return app::parse_scene(text, "<scene>");
  }
  const std::string path = py::str(py::module_::import("os").attr("fspath")(scene));
  return naming_files({path}, [&] { return app::load_scene(path); });
}

TrajectoryResult simulate(const py::object& scene, app::SimulateOptions options) {
  const std::string path =
      py::isinstance<py::dict>(scene) ? std::string() : std::string(py::str(scene));
  app::SceneDescription description = scene_of(scene);
  options.scene = description.file;
  SignalCheck check;
  std::optional<app::Trajectory> run;
  {
    py::gil_scoped_release release;
    run = naming_files({path}, [&] {
      return app::run_simulation(options, std::move(description), [&] { return check(); });
    });
  }
  check.raise_if_interrupted();
  return TrajectoryResult(std::move(*run));
}

/// Trajectory's arrays of the recorded states, each computed as the CSV writer computes its
/// columns (app/support/csv_writer.cpp).
void add_state_arrays(py::class_<TrajectoryResult>& trajectory) {
  trajectory
      .def_property_readonly("t",
                             [](const TrajectoryResult& r) {
                               return py::array_t<double>(static_cast<py::ssize_t>(r.times.size()),
                                                          r.times.data());
                             })
      .def_property_readonly("position",
                             [](const TrajectoryResult& r) {
                               return r.per_body<3>([](const auto&, const auto& s) {
                                 return Eigen::Vector3d(s.position);
                               });
                             })
      .def_property_readonly("orientation",
                             [](const TrajectoryResult& r) {
                               return r.per_body<4>([](const auto& body, const auto& s) {
                                 const Eigen::Quaterniond q = engine::body_orientation(body, s);
                                 return Eigen::Vector4d(q.w(), q.x(), q.y(), q.z());
                               });
                             })
      .def_property_readonly("velocity",
                             [](const TrajectoryResult& r) {
                               return r.per_body<3>([](const auto&, const auto& s) {
                                 return Eigen::Vector3d(s.velocity);
                               });
                             })
      .def_property_readonly("angular_velocity",
                             [](const TrajectoryResult& r) {
                               return r.per_body<3>([](const auto& body, const auto& s) {
                                 return Eigen::Vector3d(engine::angular_velocity(body, s));
                               });
                             })
      .def_property_readonly("angular_momentum",
                             [](const TrajectoryResult& r) {
                               return r.per_body<3>([](const auto&, const auto& s) {
                                 return Eigen::Vector3d(s.angular_momentum);
                               });
                             })
      .def_property_readonly("body_energy",
                             [](const TrajectoryResult& r) {
                               return r.per_body<1>([](const auto& body, const auto& s) {
                                 return Vector1d(engine::energy(body, s));
                               });
                             })
      .def_property_readonly("energy", [](const TrajectoryResult& r) {
        py::array_t<double> out(static_cast<py::ssize_t>(r.times.size()));
        double* data = out.mutable_data();
        for (const auto& step : r.states) {
          double sum = 0.0;
          for (std::size_t i = 0; i < r.bodies.size(); ++i) {
            sum += engine::energy(r.bodies[i], step[i]);
          }
          *data++ = sum;
        }
        return out;
      });
}

void bind_trajectory_class(py::module_& module) {
  py::class_<TrajectoryResult> trajectory(module, "Trajectory", R"doc(
The recorded steps of a run (the rows `tumble simulate --csv` writes: the first step, every
`every`th, the last, and after a blow-up the last good one), N steps of B bodies, SI units,
world frame.

t (N,) s; position (N, B, 3) m, the centre of mass; orientation (N, B, 4) the body frame of the
scene as a unit quaternion (w, x, y, z); velocity (N, B, 3) m/s; angular_velocity (N, B, 3)
rad/s, world frame; angular_momentum (N, B, 3) kg m^2/s about the rotation centre;
body_energy (N, B) J; energy (N,) J, the bodies' sum; body_names (B,); summary: the dict
`tumble simulate --json` prints (each body's energy and |L| drift, orientation error against
the exact solution, steps, wall_seconds); blew_up, blow_up (the one-line message or None).
to_csv(path) writes the CSV the command writes for the same run, byte for byte.
)doc");
  trajectory.attr("__module__") = "tumble";
  add_state_arrays(trajectory);
  trajectory
      .def_property_readonly("body_names",
                             [](const TrajectoryResult& r) {
                               std::vector<std::string> names;
                               for (const auto& body : r.bodies) names.push_back(body.name);
                               return names;
                             })
      .def_property_readonly(
          "summary",
          [](const TrajectoryResult& r) { return json_to_python(app::summary_to_json(r.summary)); })
      .def_property_readonly(
          "blew_up", [](const TrajectoryResult& r) { return r.summary.blow_up.has_value(); })
      .def_property_readonly("blow_up", [](const TrajectoryResult& r) { return r.summary.blow_up; })
      .def(
          "to_csv",
          [](const TrajectoryResult& r, const py::object& path) {
            const std::string file = py::str(py::module_::import("os").attr("fspath")(path));
            py::gil_scoped_release release;
            app::write_trajectory_csv(r, file);
          },
          py::arg("path"),
          "Writes the CSV `tumble simulate --csv PATH` writes for this run (atomically).")
      .def("__len__", [](const TrajectoryResult& r) { return r.times.size(); })
      .def("__repr__", [](const TrajectoryResult& r) {
        return "<tumble.Trajectory " + r.summary.scene + ": " + std::to_string(r.times.size()) +
               " steps of " + std::to_string(r.bodies.size()) + " bodies" +
               (r.summary.blow_up ? ", blew up>" : ">");
      });
}

}  // namespace

void bind_simulation(py::module_& module) {
  bind_trajectory_class(module);
  module.def(
      "simulate",
      [](const py::object& scene, std::optional<std::string> integrator, std::optional<double> dt,
         std::optional<double> duration, std::optional<double> tolerance,
         std::optional<double> absolute_tolerance, long long every,
         std::optional<double> blowup_factor, bool allow_long) {
        app::SimulateOptions options;
        options.integrator = std::move(integrator);
        options.dt = dt;
        options.duration = duration;
        options.tolerance = tolerance;
        options.absolute_tolerance = absolute_tolerance;
        options.every = every;
        options.blowup_factor = blowup_factor;
        options.allow_long = allow_long;
        return simulate(scene, options);
      },
      py::arg("scene"), py::kw_only(), py::arg("integrator") = py::none(),
      py::arg("dt") = py::none(), py::arg("duration") = py::none(),
      py::arg("tolerance") = py::none(), py::arg("absolute_tolerance") = py::none(),
      py::arg("every") = 1, py::arg("blowup_factor") = py::none(), py::arg("allow_long") = false,
      R"doc(Runs a scene without rendering, as `tumble simulate SCENE` does; returns a Trajectory.

scene: a scene file's path, or a dict in the same format (docs/scenes.md; relative mesh paths
from the working directory). The options override the scene, as the command's flags do:
integrator (a name from tumble.integrators()), dt (s), duration (s), tolerance and
absolute_tolerance (the relative and absolute tolerances of adaptive integrators; the absolute
one in each quantity's SI unit), every (record every Nth step; the first and the last always), blowup_factor
(energy or |L| growth that stops the run, default 10), allow_long (more than 1e9 steps).
A blow-up is not an error: the Trajectory says so (blew_up, blow_up) and holds the steps up to
the last good one. Ctrl-C raises KeyboardInterrupt within a fraction of a second. Raises
tumble.InputError with the command line's one-line message for bad input.)doc");
  module.def(
      "integrators", [] { return json_to_python(app::integrators_to_json()); },
      R"doc(The integrators, as `tumble simulate --list-integrators --json` lists them: a list of
dicts with name, order (global order in dt; -1 exact, 0 does not converge), adaptive,
needs_torque_free and properties (one line: what it keeps and what it breaks).)doc");
}

}  // namespace tumble::python
