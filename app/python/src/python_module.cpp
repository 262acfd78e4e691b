// The Python module `tumble._tumble`, which the package `tumble` (app/python/tumble/) re-exports:
// the library calls the command line makes, bound with numpy in and out. It links the engine,
// scene, robot and analysis libraries, never the renderer (OSMesa, LLVM) nor the viewer:
// rendering from Python runs the `tumble` executable in a child process (tumble/__init__.py).
#include "mass_bindings.hpp"
#include "python_support.hpp"
#include "robot_bindings.hpp"
#include "simulation_bindings.hpp"

PYBIND11_MODULE(_tumble, module) {
  module.doc() = "tumble: mass properties of meshes, rigid-body dynamics (compiled part)";
  tumble::python::bind_input_error(module);
  tumble::python::bind_mass(module);
  tumble::python::bind_robot(module);
  tumble::python::bind_simulation(module);
  module.attr("__version__") = TUMBLE_VERSION;
  // Where tumble/__init__.py looks for the `tumble` executable (after $TUMBLE_EXECUTABLE).
  module.def("_executable_candidates", [] {
    return pybind11::make_tuple(TUMBLE_EXECUTABLE_BUILT, TUMBLE_EXECUTABLE_INSTALLED);
  });
}
