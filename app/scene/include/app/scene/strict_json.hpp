#pragma once
/// @file Reading JSON written by people: comments allowed, mistakes reported precisely.

#include <string>

#include <nlohmann/json.hpp>

namespace tumble::app {

/// Parses `text` (JSON with // and /* */ comments). Throws engine::InputError with a one-line
/// message starting with `source`:
///  - syntax errors: "SOURCE:LINE:COLUMN: malformed JSON: reason";
///  - numbers beyond the range of a double (1e999, which JSON allows but nothing can hold):
///    "SOURCE:LINE:COLUMN: PATH: expected a finite number, got 1e999";
///  - a key given twice in one object (the first would be silently lost):
///    "SOURCE: PATH: duplicate key".
/// PATH is the value's JSON path, e.g. `bodies[0].mass`.
nlohmann::json parse_strict_json(const std::string& text, const std::string& source);

}  // namespace tumble::app
