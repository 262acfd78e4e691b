// Primitive shapes in scene files: {"kind": dimensions} to engine::Shape (shape_field.hpp).
#include "app/scene/shape_field.hpp"

#include <cstddef>
#include <string>
#include <string_view>
#include <utility>

#include "base/errors.hpp"

namespace tumble::app {
namespace {

constexpr const char* kKinds =
    "{\"box\": [x, y, z]}, {\"sphere\": {\"radius\": r}}, {\"cylinder\": {\"radius\": r, "
    "\"length\": l}}, {\"capsule\": {\"radius\": r, \"length\": l}}, {\"ellipsoid\": [a, b, c]} "
    "or {\"cone\": {\"radius\": r, \"height\": h}}";

/// [x, y, z] of positive numbers (each element's path names it on error).
Eigen::Vector3d positive_vector3(const JsonField& field, const std::string& what) {
  field.expect_array(3, what);
  return {field.element(0).positive(), field.element(1).positive(), field.element(2).positive()};
}

/// {"radius": r, `second`: x} of positive numbers, both required.
std::pair<double, double> radius_and(const JsonField& field, std::string_view second,
                                     const std::string& second_meaning) {
  field.expect_object({"radius", second});
  const double radius = field.require("radius", "the radius in metres (positive)").positive();
  return {radius, field.require(second, second_meaning).positive()};
}

engine::Shape parse_kind(const std::string& kind, const JsonField& value) {
  if (kind == "box") {
    return engine::Box{positive_vector3(value, "the edge lengths [x, y, z] of 3 positive numbers")};
  }
  if (kind == "ellipsoid") {
    return engine::Ellipsoid{
        positive_vector3(value, "the semi-axes [a, b, c] of 3 positive numbers")};
  }
  if (kind == "sphere") {
    value.expect_object({"radius"});
    return engine::Sphere{value.require("radius", "the radius in metres (positive)").positive()};
  }
  if (kind == "cylinder") {
    const auto [radius, length] =
        radius_and(value, "length", "the length along z in metres, end to end (positive)");
    return engine::Cylinder{radius, length};
  }
  if (kind == "capsule") {
    const auto [radius, length] = radius_and(
        value, "length", "the length of the cylindrical part in metres, caps excluded (positive)");
    return engine::Capsule{radius, length};
  }
  const auto [radius, height] =
      radius_and(value, "height", "the height from base to apex in metres (positive)");
  return engine::Cone{radius, height};
}

}  // namespace

engine::Shape parse_shape(const JsonField& field) {
  field.expect_object({"box", "sphere", "cylinder", "capsule", "ellipsoid", "cone"});
  if (field.value().size() != 1) {
    const std::size_t keys = field.value().size();
    field.fail("expected exactly one of " + std::string(kKinds) + ", got " +
               (keys == 0 ? std::string("an empty object") : std::to_string(keys) + " kinds"));
  }
  const std::string kind = field.value().begin().key();
  const engine::Shape shape = parse_kind(kind, *field.find(kind));
  try {
    engine::validate_shape(shape);  // each number is positive: what is left is its range
  } catch (const tumble::InputError& error) {
    field.fail(error.what());
  }
  return shape;
}

}  // namespace tumble::app
