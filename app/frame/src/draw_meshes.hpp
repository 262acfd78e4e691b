#pragma once
// Meshes as the renderer wants them: float vertices with shading normals (private to the app's
// frame builder).

#include <Eigen/Core>

#include "engine/geometry/triangle_mesh.hpp"
#include "render/draw_list.hpp"

namespace tumble::app::detail {

/// The mesh with three vertices per triangle and smooth normals: each corner averages the
/// area-weighted normals of the triangles around its vertex that turn less than
/// `crease_angle_deg` from its own, so curved surfaces look round and edges stay sharp. Marked
/// closed (its back faces hidden from outside) when engine::bounds_outward_solids holds.
render::MeshData shaded_mesh_data(const engine::TriangleMesh& mesh, double crease_angle_deg);

/// A latitude-longitude ellipsoid of semi-axes `radii` with its exact normals.
render::MeshData ellipsoid_mesh_data(const Eigen::Vector3d& radii);

/// Largest distance of a vertex from the origin (m).
double bounding_radius(const engine::TriangleMesh& mesh);

}  // namespace tumble::app::detail
