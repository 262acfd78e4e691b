#pragma once
// JSON values (nlohmann) as Python objects, so that a result's to_dict() is exactly the JSON the
// command line prints: objects as dicts (keys in the JSON's order), arrays as lists, numbers as
// int or float, "nan"/"inf" strings left as strings.

#include <pybind11/pybind11.h>

#include <nlohmann/json.hpp>

namespace tumble::python {

pybind11::object json_to_python(const nlohmann::json& value);

}  // namespace tumble::python
