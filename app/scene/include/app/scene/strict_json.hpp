#pragma once
/// @file Reading JSON written by people: comments allowed, mistakes reported precisely.

#include <cstddef>
#include <string>

#include <nlohmann/json.hpp>

namespace tumble::app {

/// Parses `text` (JSON with // and /* */ comments). Throws tumble::InputError with a one-line
/// message starting with `source`:
///  - syntax errors: "SOURCE:LINE:COLUMN: malformed JSON: reason";
///  - numbers beyond the range of a double (1e999, which JSON allows but nothing can hold):
///    "SOURCE:LINE:COLUMN: PATH: expected a finite number, got 1e999";
///  - a key given twice in one object (the first would be silently lost):
///    "SOURCE: PATH: duplicate key";
///  - arrays and objects nested more than kMaxJsonDepth levels deep:
///    "SOURCE: PATH: nested deeper than 256 levels of arrays and objects".
/// Memory is linear in the size of `text` (no scene needs more than a few levels).
/// PATH is the value's JSON path, e.g. `bodies[0].mass`.
inline constexpr std::size_t kMaxJsonDepth = 256;

nlohmann::json parse_strict_json(const std::string& text, const std::string& source);

}  // namespace tumble::app
