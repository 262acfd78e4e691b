#pragma once
/// @file Reading validated values out of JSON, with the file and JSON path in every message.

#include <cstddef>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

namespace tumble::app {

/// Shortest text that reads back as the same double ("inf", "-inf", "nan" for the rest).
std::string number_text(double value);

/// What a JSON value is, for "expected X, got Y" messages.
std::string describe(const nlohmann::json& value);

/// One value of a JSON document and where it sits (file and JSON path, e.g.
/// `bodies[0].angular_velocity`), so that every error can name both. Every accessor checks
/// the type and range and throws tumble::InputError "FILE: PATH: expected ..., got ...".
class JsonField {
 public:
  JsonField(const nlohmann::json& value, std::string path, const std::string& file);

  const nlohmann::json& value() const { return value_; }
  const std::string& path() const { return path_; }

  /// Throws "FILE: PATH: what".
  [[noreturn]] void fail(const std::string& what) const;

  /// The object's member `key`, or nothing when it is absent.
  std::optional<JsonField> find(std::string_view key) const;
  /// The object's member `key`; `expected` says what it should be when it is missing.
  JsonField require(std::string_view key, const std::string& expected) const;
  /// The array's element `index` (which must exist).
  JsonField element(std::size_t index) const;

  /// Checks this is an object whose keys are all in `allowed` (the message lists them).
  void expect_object(std::initializer_list<std::string_view> allowed) const;
  /// Checks this is an array of exactly `size` entries; `what` describes the expected value.
  void expect_array(std::size_t size, const std::string& what) const;

  double number() const;  ///< finite
  double positive() const;
  double non_negative() const;
  double in_range(double low, double high) const;
  int integer(int low, int high) const;  ///< a whole number in [low, high]
  bool boolean() const;
  std::string string() const;
  Eigen::Vector3d vector3() const;  ///< [x, y, z], finite

 private:
  std::string child_path(std::string_view key) const;

  const nlohmann::json& value_;
  std::string path_;
  const std::string& file_;
};

}  // namespace tumble::app
