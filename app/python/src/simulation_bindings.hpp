#pragma once
// The dynamics half of the module: tumble.simulate and its Trajectory, tumble.integrators
// (simulation_bindings.cpp).

#include "python_support.hpp"

namespace tumble::python {

void bind_simulation(py::module_& module);

}  // namespace tumble::python
