// Primitive solids: validation, closed-form volumes and inertias, tessellations.
//
// The closed forms are the standard tables of homogeneous solids (e.g. Meriam, Kraige,
// Engineering Mechanics: Dynamics, appendix "Properties of homogeneous solids"); the capsule
// is assembled from a cylinder and two hemispheres by the parallel-axis theorem, the ellipsoid
// is the unit ball stretched. Derivations: engine/PHYSICS.md §9.
#include "engine/mass/primitive_shapes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/errors.hpp"
#include "engine/geometry/primitive_meshes.hpp"

namespace tumble::engine {
namespace {

constexpr double kPi = std::numbers::pi;

// Overloaded visitor (the usual C++17 idiom).
template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

/// Shortest round-tripping text of a double, for messages.
std::string number_text(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char text[32];
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(text, sizeof text, "%.*g", digits, value);
    if (std::strtod(text, nullptr) == value) break;
  }
  return text;
}

void require_dimension(double value, std::string_view kind, const std::string& field) {
  if (!(std::isfinite(value) && value > 0.0)) {
    throw InputError(std::string(kind) + " " + field + ": expected a positive finite number, got " +
                     number_text(value));
  }
}

void require_dimensions(const Eigen::Vector3d& values, std::string_view kind,
                        const std::string& field) {
  for (int i = 0; i < 3; ++i) {
    require_dimension(values[i], kind, field + "[" + std::to_string(i) + "]");
  }
}

/// A value derived from valid dimensions (volume, moment) that overflowed or underflowed.
bool representable(double value) {
  return std::isfinite(value) && value >= std::numeric_limits<double>::min();
}

/// Diagonal tensor with entries (a, b, c).
Eigen::Matrix3d diagonal(double a, double b, double c) {
  return Eigen::Vector3d(a, b, c).asDiagonal();
}

/// Unit-mass inertia of a solid whose second moment per unit mass is diag(s): tr(s) 1 - s.
Eigen::Matrix3d from_second_moment(const Eigen::Vector3d& s) {
  return diagonal(s[1] + s[2], s[0] + s[2], s[0] + s[1]);
}

double volume_unchecked(const Shape& shape) {
  return std::visit(
      Overloaded{
          [](const Box& b) { return b.size.prod(); },
          [](const Sphere& s) { return 4.0 / 3.0 * kPi * s.radius * s.radius * s.radius; },
          [](const Cylinder& c) { return kPi * c.radius * c.radius * c.length; },
          [](const Capsule& c) {
            return kPi * c.radius * c.radius * (c.length + 4.0 / 3.0 * c.radius);
          },
          [](const Ellipsoid& e) { return 4.0 / 3.0 * kPi * e.radii.prod(); },
          [](const Cone& c) { return kPi * c.radius * c.radius * c.height / 3.0; },
      },
      shape);
}

/// Capsule of radius r and cylinder length l (PHYSICS.md §9): the cylinder's mass fraction
/// f_c = l / (l + 4r/3), the caps' f_h = 1 - f_c; about the axis
/// f_c r^2/2 + f_h 2r^2/5; across it f_c (r^2/4 + l^2/12) + f_h (2r^2/5 + l^2/4 + 3lr/8), the
/// last term the two hemispheres (centre of mass 3r/8 from the flat face) moved to the middle.
Eigen::Matrix3d capsule_unit_inertia(const Capsule& c) {
  const double r = c.radius;
  const double l = c.length;
  const double f_cylinder = l / (l + 4.0 / 3.0 * r);
  const double f_caps = (4.0 / 3.0 * r) / (l + 4.0 / 3.0 * r);
  const double axial = f_cylinder * r * r / 2.0 + f_caps * 2.0 * r * r / 5.0;
  const double transverse = f_cylinder * (r * r / 4.0 + l * l / 12.0) +
                            f_caps * (2.0 * r * r / 5.0 + l * l / 4.0 + 3.0 * l * r / 8.0);
  return diagonal(transverse, transverse, axial);
}

Eigen::Matrix3d unit_inertia_unchecked(const Shape& shape) {
  return std::visit(
      Overloaded{
          [](const Box& b) { return from_second_moment(b.size.cwiseAbs2() / 12.0); },
          [](const Sphere& s) {
            const double moment = 0.4 * s.radius * s.radius;
            return diagonal(moment, moment, moment);
          },
          [](const Cylinder& c) {
            const double transverse = c.radius * c.radius / 4.0 + c.length * c.length / 12.0;
            return diagonal(transverse, transverse, c.radius * c.radius / 2.0);
          },
          [](const Capsule& c) { return capsule_unit_inertia(c); },
          [](const Ellipsoid& e) { return from_second_moment(e.radii.cwiseAbs2() / 5.0); },
          [](const Cone& c) {
            const double r2 = c.radius * c.radius;
            const double transverse = 3.0 / 20.0 * r2 + 3.0 / 80.0 * c.height * c.height;
            return diagonal(transverse, transverse, 3.0 / 10.0 * r2);
          },
      },
      shape);
}

void require_matter(double value, const char* what) {
  if (!(std::isfinite(value) && value > 0.0)) {
    throw InputError(std::string(what) + ": expected a positive finite number, got " +
                     number_text(value));
  }
}

/// The profile (r, z) of the capsule from its lower pole to its upper one: each cap a quarter
/// circle in `bands` equal steps of polar angle, inscribed; the cylinder one straight band.
TriangleMesh capsule_mesh(const Capsule& c, int segments) {
  const int bands = std::max(1, segments / 4);
  const double half = 0.5 * c.length;
  std::vector<Eigen::Vector2d> profile;
  profile.emplace_back(0.0, -half - c.radius);
  for (int k = 1; k <= bands; ++k) {  // the lower cap, from the pole to its equator
    const double polar = 0.5 * kPi * static_cast<double>(k) / static_cast<double>(bands);
    profile.emplace_back(c.radius * std::sin(polar), -half - c.radius * std::cos(polar));
  }
  // The upper cap from its equator to the pole: the lower cap's points mirrored, reversed.
  for (int k = bands; k >= 1; --k) {
    const Eigen::Vector2d& p = profile[static_cast<std::size_t>(k)];
    profile.emplace_back(p.x(), -p.y());
  }
  profile.emplace_back(0.0, half + c.radius);
  return revolve_profile(profile, segments);
}

TriangleMesh tessellate_valid(const Shape& shape, int segments) {
  const int rings = std::max(2, segments / 2);
  return std::visit(
      Overloaded{
          [](const Box& b) { return box_mesh(b.size); },
          [&](const Sphere& s) { return uv_sphere_mesh(s.radius, segments, rings); },
          [&](const Cylinder& c) { return cylinder_mesh(c.radius, c.length, segments); },
          [&](const Capsule& c) { return capsule_mesh(c, segments); },
          [&](const Ellipsoid& e) { return ellipsoid_mesh(e.radii, segments, rings); },
          [&](const Cone& c) {
            TriangleMesh mesh = cone_mesh(c.radius, c.height, segments);
            transform_mesh(mesh, Eigen::Matrix3d::Identity(),
                           Eigen::Vector3d(0.0, 0.0, -0.25 * c.height));
            return mesh;
          },
      },
      shape);
}

}  // namespace

std::string_view shape_kind(const Shape& shape) {
  return std::visit(Overloaded{
                        [](const Box&) { return std::string_view("box"); },
                        [](const Sphere&) { return std::string_view("sphere"); },
                        [](const Cylinder&) { return std::string_view("cylinder"); },
                        [](const Capsule&) { return std::string_view("capsule"); },
                        [](const Ellipsoid&) { return std::string_view("ellipsoid"); },
                        [](const Cone&) { return std::string_view("cone"); },
                    },
                    shape);
}

void validate_shape(const Shape& shape) {
  const std::string_view kind = shape_kind(shape);
  std::visit(Overloaded{
                 [&](const Box& b) { require_dimensions(b.size, kind, "size"); },
                 [&](const Sphere& s) { require_dimension(s.radius, kind, "radius"); },
                 [&](const Cylinder& c) {
                   require_dimension(c.radius, kind, "radius");
                   require_dimension(c.length, kind, "length");
                 },
                 [&](const Capsule& c) {
                   require_dimension(c.radius, kind, "radius");
                   require_dimension(c.length, kind, "length");
                 },
                 [&](const Ellipsoid& e) { require_dimensions(e.radii, kind, "radii"); },
                 [&](const Cone& c) {
                   require_dimension(c.radius, kind, "radius");
                   require_dimension(c.height, kind, "height");
                 },
             },
             shape);
  const double v = volume_unchecked(shape);
  const Eigen::Vector3d moments = unit_inertia_unchecked(shape).diagonal();
  if (!representable(v) || !representable(moments.minCoeff()) ||
      !representable(moments.maxCoeff())) {
    throw InputError(std::string(kind) + ": its volume (" + number_text(v) +
                     " m^3) or moments of inertia are beyond the range of a double");
  }
}

double volume(const Shape& shape) {
  validate_shape(shape);
  return volume_unchecked(shape);
}

Eigen::Matrix3d unit_inertia(const Shape& shape) {
  validate_shape(shape);
  return unit_inertia_unchecked(shape);
}

MassProperties mass_properties(const Shape& shape, double density) {
  require_matter(density, "density");
  const double mass = density * volume(shape);
  if (!representable(mass)) {
    throw InputError(std::string(shape_kind(shape)) + ": the mass density * volume = " +
                     number_text(mass) + " kg is beyond the range of a double");
  }
  return mass_properties_of_mass(shape, mass);
}

MassProperties mass_properties_of_mass(const Shape& shape, double mass) {
  require_matter(mass, "mass");
  MassProperties properties;
  properties.mass = mass;
  properties.inertia = mass * unit_inertia(shape);
  const Eigen::Vector3d moments = properties.inertia.diagonal();
  if (!representable(moments.minCoeff()) || !representable(moments.maxCoeff())) {
    throw InputError(std::string(shape_kind(shape)) + ": its moments of inertia for a mass of " +
                     number_text(mass) + " kg are beyond the range of a double");
  }
  return properties;
}

TriangleMesh tessellate(const Shape& shape, int segments) {
  validate_shape(shape);
  if (segments < 4) {
    throw InputError("tessellate: expected at least 4 segments, got " + std::to_string(segments));
  }
  try {
    return tessellate_valid(shape, segments);
  } catch (const std::invalid_argument& error) {  // e.g. a capsule too short to resolve
    throw InputError(std::string(shape_kind(shape)) + ": cannot tessellate: " + error.what());
  }
}

}  // namespace tumble::engine
