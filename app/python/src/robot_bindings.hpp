#pragma once
// The robot half of the module: tumble.inertials and the RobotInertials it returns
// (robot_bindings.cpp).

#include "python_support.hpp"

namespace tumble::python {

void bind_robot(py::module_& module);

}  // namespace tumble::python
