#pragma once
// --overlap union: parts that overlap, nest with the same orientation or repeat are replaced by
// their exact union (engine/overlap/solids.hpp), the other parts (cavities included) counted as
// they are. The union is CGAL's corefinement with exact constructions; its vertices are rounded
// to doubles only at the end, so its integrals are those of the exact union to rounding.

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "engine/geometry/mesh_topology.hpp"
#include "engine/geometry/triangle_mesh.hpp"
#include "engine/mass/mass_properties.hpp"
#include "engine/mass/mesh_analysis.hpp"

namespace tumble::engine::detail {

/// The volume integrals of `mesh` (welded, closed, every part wound as it is to be counted)
/// with the parts `united` replaced by their union, about `reference`. Notes the union in
/// `report` (united_parts, shared_volume, a warning with the shared volume and its fraction of
/// the mesh's). Throws InputError naming report.source when the union cannot be computed.
MomentIntegrals united_integrals(const TriangleMesh& mesh, const Topology& topology,
                                 const std::vector<std::uint32_t>& united,
                                 const Eigen::Vector3d& reference, MeshReport& report);

}  // namespace tumble::engine::detail
