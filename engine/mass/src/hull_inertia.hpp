#pragma once
// The convex method: a mesh's inertia taken as that of its convex hull's solid.

#include <optional>

#include <Eigen/Core>

#include "engine/geometry/triangle_mesh.hpp"
#include "engine/mass/mesh_analysis.hpp"

namespace tumble::engine::detail {

/// Fills `report` (volume, density, mass properties) with the solid of the convex hull of
/// `mesh`'s vertices, about `reference`, and states the hull's volume beside
/// `enclosed_volume` (the solid the mesh itself encloses, when it is one), warning when they
/// differ by more than 5%. Throws InputError when the vertices span no volume.
void convex_properties(const TriangleMesh& mesh, const Eigen::Vector3d& reference,
                       const MassOptions& options, std::optional<double> enclosed_volume,
                       MeshReport& report);

}  // namespace tumble::engine::detail
