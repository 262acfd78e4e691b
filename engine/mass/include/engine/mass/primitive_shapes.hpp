#pragma once
/// @file Primitive solids given by their dimensions, with exact analytic mass properties.
///
/// Conventions (those of URDF, SDF and MJCF where they agree; engine/PHYSICS.md §9):
///  - every shape is centred at the origin with its centre of mass there, its axis (if it has
///    one) along z, and its axes of symmetry along x, y, z: the inertia tensor is diagonal;
///  - Box: full edge lengths `size` along x, y, z (URDF/SDF `size`, not MJCF's half sizes);
///  - Cylinder: `radius` and full `length` along z, z in [-length/2, length/2];
///  - Capsule: `radius` and the `length` of the cylindrical part only (SDF; MJCF gives half
///    of it): the caps' poles are at z = +-(length/2 + radius), the whole solid is
///    length + 2 radius long;
///  - Ellipsoid: semi-axes `radii` along x, y, z;
///  - Cone: base `radius` and `height`, apex up. URDF and MJCF have no cone; here the base is
///    at z = -height/4 and the apex at z = 3 height/4, so that the centre of mass (a quarter
///    of the height above the base) is the origin like every other shape's.
/// Dimensions are metres. Every function below first validates the shape: each dimension must
/// be positive and finite, and its volume and moments representable (positive, finite
/// doubles), or it throws tumble::InputError naming the field ("cylinder length: ...").

#include <Eigen/Core>
#include <string_view>
#include <variant>

#include "engine/geometry/triangle_mesh.hpp"
#include "engine/mass/mass_properties.hpp"

namespace tumble::engine {

struct Box {
  Eigen::Vector3d size = Eigen::Vector3d::Ones();  ///< full edge lengths along x, y, z (m)
};
struct Sphere {
  double radius = 1.0;  ///< m
};
struct Cylinder {
  double radius = 1.0;  ///< m
  double length = 1.0;  ///< along z, end to end (m)
};
struct Capsule {
  double radius = 1.0;  ///< of the cylinder and of the two hemispherical caps (m)
  double length = 1.0;  ///< of the cylindrical part alone, along z (m)
};
struct Ellipsoid {
  Eigen::Vector3d radii = Eigen::Vector3d::Ones();  ///< semi-axes along x, y, z (m)
};
struct Cone {
  double radius = 1.0;  ///< of the base (m)
  double height = 1.0;  ///< base to apex along z (m); base at z = -height/4
};

/// One primitive solid.
using Shape = std::variant<Box, Sphere, Cylinder, Capsule, Ellipsoid, Cone>;

/// The shape's kind as scene files spell it: "box", "sphere", "cylinder", "capsule",
/// "ellipsoid" or "cone".
std::string_view shape_kind(const Shape& shape);

/// Throws tumble::InputError naming the first bad field ("box size[1]: expected a positive
/// finite number, got -1"), or the whole shape when its volume or moments overflow or
/// underflow a double.
void validate_shape(const Shape& shape);

/// Volume (m^3).
double volume(const Shape& shape);

/// Inertia tensor per unit mass about the centre of mass (m^2), diagonal: the closed forms of
/// engine/PHYSICS.md §9.
Eigen::Matrix3d unit_inertia(const Shape& shape);

/// Mass properties of the shape filled with uniform matter of `density` (kg/m^3, positive and
/// finite): mass density * volume, centre of mass the origin, inertia mass * unit_inertia.
MassProperties mass_properties(const Shape& shape, double density);

/// The same for a given total `mass` (kg, positive and finite), which is kept exactly.
MassProperties mass_properties_of_mass(const Shape& shape, double mass);

/// A closed, outward-wound mesh of the shape for drawing and for checks: `segments` (>= 4)
/// around the z axis, inscribed in the true surface (curved parts only; a box is its 12
/// triangles whatever `segments`). Spheres and ellipsoids have segments/2 latitude bands, each
/// capsule cap segments/4 (at least 1). The cone's base is at z = -height/4 as above.
TriangleMesh tessellate(const Shape& shape, int segments);

}  // namespace tumble::engine
