#pragma once
/// @file Solids built from a mesh's surfaces with exact geometry: the union of overlapping parts
/// and the convex hull of a point set, each as a closed, outward-wound triangle mesh whose
/// mass properties the ordinary integrals then give.
///
/// Both are computed by CGAL: the union by corefinement (Polygon Mesh Processing,
/// corefine_and_compute_union) with exact constructions, so that the new vertices where two
/// surfaces cross are exact until they are rounded to doubles at the end; the hull by
/// quickhull with exact predicates (convex_hull_3), whose vertices are input points.

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "engine/geometry/triangle_mesh.hpp"

namespace tumble::engine {

/// The union of some parts of `mesh` (welded; `triangle_part` numbers each triangle's part):
/// the parts listed in `parts`, each closed, consistently wound outward and free of
/// self-intersections, merged into the closed surface(s) bounding the space any of them fills.
/// Throws std::runtime_error when CGAL cannot compute it (a part that does not bound a volume).
TriangleMesh union_of_parts(const TriangleMesh& mesh,
                            const std::vector<std::uint32_t>& triangle_part,
                            const std::vector<std::uint32_t>& parts);

/// The convex hull of `points` as a closed mesh wound outward. Throws tumble::InputError
/// "SOURCE: ..." when the points span no volume (fewer than four, or all in one plane).
TriangleMesh convex_hull_mesh(const std::vector<Eigen::Vector3d>& points,
                              const std::string& source);

}  // namespace tumble::engine
