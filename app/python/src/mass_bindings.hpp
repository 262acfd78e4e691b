#pragma once
// The mass-property half of the module: tumble.MassProperties, inspect, mass_properties,
// primitive (mass_bindings.cpp).

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "engine/mass/mesh_analysis.hpp"
#include "engine/mass/primitive_shapes.hpp"
#include "python_support.hpp"

namespace tumble::python {

/// What tumble.MassProperties holds: the report `tumble inspect` prints, the method that
/// computed it, and its JSON object (to_dict).
struct MassPropertiesResult {
  explicit MassPropertiesResult(engine::MeshReport mesh);
  MassPropertiesResult(const engine::Shape& shape, const engine::MassProperties& properties);

  std::optional<engine::MeshReport> report;
  std::string method;
  nlohmann::json dictionary;
};

void bind_mass(py::module_& module);

}  // namespace tumble::python
