// Validated JSON values with file and path in every message.
#include "app/scene/json_field.hpp"

#include <charconv>
#include <cmath>

#include "base/errors.hpp"

namespace tumble::app {

using tumble::InputError;
namespace {
using nlohmann::json;  // file-local (a namespace-wide name would shadow `json` members)
}  // namespace

std::string number_text(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

std::string describe(const json& value) {
  switch (value.type()) {
    case json::value_t::null:
      return "null";
    case json::value_t::boolean:
      return value.get<bool>() ? "true" : "false";
    case json::value_t::string:
      return "the string \"" + value.get<std::string>() + "\"";
    case json::value_t::array:
      return "an array of " + std::to_string(value.size());
    case json::value_t::object:
      return "an object";
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
    case json::value_t::number_float:
      return number_text(value.get<double>());
    default:
      return "an unsupported value";
  }
}

JsonField::JsonField(const json& value, std::string path, const std::string& file)
    : value_(value), path_(std::move(path)), file_(file) {}

void JsonField::fail(const std::string& what) const {
  throw InputError(file_ + ": " + (path_.empty() ? std::string("(top level)") : path_) + ": " +
                   what);
}

std::string JsonField::child_path(std::string_view key) const {
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

std::optional<JsonField> JsonField::find(std::string_view key) const {
  const auto it = value_.find(key);
  if (it == value_.end()) return std::nullopt;
  return JsonField(*it, child_path(key), file_);
}

JsonField JsonField::require(std::string_view key, const std::string& expected) const {
  if (auto found = find(key)) return *found;
  throw InputError(file_ + ": " + child_path(key) + ": missing; expected " + expected);
}

JsonField JsonField::element(std::size_t index) const {
  return JsonField(value_[index], path_ + "[" + std::to_string(index) + "]", file_);
}

void JsonField::expect_object(std::initializer_list<std::string_view> allowed) const {
  if (!value_.is_object()) fail("expected an object, got " + describe(value_));
  for (const auto& [key, member] : value_.items()) {
    bool known = false;
    for (std::string_view name : allowed) known = known || key == name;
    if (known) continue;
    std::string names;
    for (std::string_view name : allowed) names += (names.empty() ? "" : ", ") + std::string(name);
    throw InputError(file_ + ": " + child_path(key) + ": unknown key; expected one of: " + names);
  }
}

void JsonField::expect_array(std::size_t size, const std::string& what) const {
  if (!value_.is_array() || value_.size() != size) {
    fail("expected " + what + ", got " + describe(value_));
  }
}

double JsonField::number() const {
  if (!value_.is_number()) fail("expected a number, got " + describe(value_));
  const double result = value_.get<double>();
  if (!std::isfinite(result)) {
    fail("expected a finite number, got " + number_text(result) +
         " (JSON numbers beyond +-1.8e308 read as infinity)");
  }
  return result;
}

double JsonField::positive() const {
  const double result = number();
  if (!(result > 0.0)) fail("expected a positive number, got " + number_text(result));
  return result;
}

double JsonField::non_negative() const {
  const double result = number();
  if (result < 0.0) fail("expected a number >= 0, got " + number_text(result));
  return result;
}

double JsonField::in_range(double low, double high) const {
  const double result = number();
  if (result < low || result > high) {
    fail("expected a number from " + number_text(low) + " to " + number_text(high) + ", got " +
         number_text(result));
  }
  return result;
}

int JsonField::integer(int low, int high) const {
  const double result = number();
  if (result != std::floor(result) || result < low || result > high) {
    fail("expected a whole number from " + std::to_string(low) + " to " + std::to_string(high) +
         ", got " + number_text(result));
  }
  return static_cast<int>(result);
}

bool JsonField::boolean() const {
  if (!value_.is_boolean()) fail("expected true or false, got " + describe(value_));
  return value_.get<bool>();
}

std::string JsonField::string() const {
  if (!value_.is_string()) fail("expected a string, got " + describe(value_));
  return value_.get<std::string>();
}

Eigen::Vector3d JsonField::vector3() const {
  expect_array(3, "an array of 3 finite numbers [x, y, z]");
  return {element(0).number(), element(1).number(), element(2).number()};
}

}  // namespace tumble::app
