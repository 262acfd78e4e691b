#pragma once
/// @file Exact mass properties of closed polyhedra and thin shells.
///
/// The solid integrals sum signed tetrahedra spanned by a reference point and each triangle
/// (divergence theorem; e.g. Tonon, "Explicit exact formulas for the 3-D tetrahedron inertia
/// tensor", J. Math. Stat. 1 (2005)): with a' = a - r etc., det = a'.(b' x c') = 6V_tet,
/// first moment V_tet (a'+b'+c')/4, second moment V_tet/20 (a'a'^T + b'b'^T + c'c'^T + s s^T).
/// Accumulating about a point near the mesh (not the world origin) keeps far-away meshes exact.

#include <vector>

#include <Eigen/Core>

#include "engine/geometry/triangle_mesh.hpp"

namespace tumble::engine {

/// Integrals of 1, (x - r) and (x - r)(x - r)^T over a solid (or a surface, for shells).
struct MomentIntegrals {
  double measure = 0.0;           ///< volume (m^3) or area (m^2)
  double absolute_measure = 0.0;  ///< sum of |signed parts| of `measure`: its rounding scale
  Eigen::Vector3d first = Eigen::Vector3d::Zero();   ///< integral of (x - r)
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();  ///< integral of (x - r)(x - r)^T
};

/// Volume integrals of the solid bounded by a closed, outward-wound mesh, about `reference`.
MomentIntegrals solid_integrals(const TriangleMesh& mesh, const Eigen::Vector3d& reference);

/// Area integrals of the surface (each triangle weighted by its area), about `reference`.
MomentIntegrals surface_integrals(const TriangleMesh& mesh, const Eigen::Vector3d& reference);

/// Mass, centre of mass and inertia tensor about the centre of mass.
struct MassProperties {
  double mass = 0.0;                                         ///< kg
  Eigen::Vector3d center_of_mass = Eigen::Vector3d::Zero();  ///< m
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();         ///< kg m^2, about the centre of mass

  /// The same body moved by `offset` (the inertia about the centre of mass is unchanged).
  MassProperties translated(const Eigen::Vector3d& offset) const;
  /// The same body turned by the rotation `rotation` about the world origin.
  MassProperties rotated(const Eigen::Matrix3d& rotation) const;
  /// Inertia tensor about an arbitrary point (parallel-axis theorem).
  Eigen::Matrix3d inertia_about(const Eigen::Vector3d& point) const;
};

/// Mass properties of uniform matter of `density` (per unit of the integrals' measure)
/// filling the integrals, which were taken about `reference`.
MassProperties mass_properties(const MomentIntegrals& integrals, const Eigen::Vector3d& reference,
                               double density);

/// The mass properties of several bodies held together: masses add, the centre of mass is the
/// mass-weighted mean, and each inertia is carried to it by the parallel-axis theorem. All
/// must be in one frame. Throws std::invalid_argument when `parts` is empty or the total mass is
/// not positive.
MassProperties combined(const std::vector<MassProperties>& parts);

/// Inertia tensor rho (tr(C) 1 - C) of a second moment C.
Eigen::Matrix3d inertia_from_second_moment(const Eigen::Matrix3d& second_moment, double density);

}  // namespace tumble::engine
