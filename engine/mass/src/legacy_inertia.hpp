#pragma once
// The legacy method: a mesh's inertia as MuJoCo 2.2.2 computes it by default, an approximation
// that differs from the exact solid on every mesh but a box. MuJoCo 3's <mesh inertia="legacy">
// names the same idea but computes it otherwise (docs/inspect.md); this is 2.2.2's.

#include <optional>

#include "engine/geometry/triangle_mesh.hpp"
#include "engine/mass/mesh_analysis.hpp"

namespace tumble::engine::detail {

/// Fills `report` (volume, density, mass properties) as MuJoCo's legacy mesh inertia does, and
/// warns how far `enclosed_volume` (the exact solid's, when exact accepts the mesh) is from it.
/// Any triangle soup is accepted; throws InputError when it has no area or no volume.
void legacy_properties(const TriangleMesh& mesh, const MassOptions& options,
                       std::optional<double> enclosed_volume, MeshReport& report);

}  // namespace tumble::engine::detail
