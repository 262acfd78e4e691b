// The union of overlapping parts and the convex hull (solids.hpp). One of the files that include
// CGAL (compiled with its flags, in the geometry unit's CGAL object library).
#include "engine/geometry/solids.hpp"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>

#include <map>
#include <stdexcept>

#include "base/errors.hpp"

namespace tumble::engine {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using ExactKernel = CGAL::Exact_predicates_exact_constructions_kernel;
using ExactMesh = CGAL::Surface_mesh<ExactKernel::Point_3>;
using HullKernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using HullMesh = CGAL::Surface_mesh<HullKernel::Point_3>;

/// The triangles of part `part` as a surface mesh of exact points.
ExactMesh part_surface(const TriangleMesh& mesh, const std::vector<std::uint32_t>& triangle_part,
                       std::uint32_t part) {
  ExactMesh surface;
  std::map<std::uint32_t, ExactMesh::Vertex_index> vertex_of;
  const auto vertex = [&](std::uint32_t v) {
    const auto [at, added] = vertex_of.try_emplace(v);
    if (added) {
      const Eigen::Vector3d& p = mesh.positions[v];
      at->second = surface.add_vertex(ExactKernel::Point_3(p.x(), p.y(), p.z()));
    }
    return at->second;
  };
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (triangle_part[t] != part) continue;
    const auto& tri = mesh.triangles[t];
    if (surface.add_face(vertex(tri[0]), vertex(tri[1]), vertex(tri[2])) ==
        ExactMesh::null_face()) {
      throw std::runtime_error("part " + std::to_string(part + 1) + " is not a manifold surface");
    }
  }
  return surface;
}

/// A surface mesh of triangles into a TriangleMesh, its points rounded to doubles.
template <typename Surface>
TriangleMesh triangle_mesh(const Surface& surface) {
  TriangleMesh out;
  std::map<typename Surface::Vertex_index, std::uint32_t> index;
  for (const auto v : surface.vertices()) {
    const auto& p = surface.point(v);
    index[v] = static_cast<std::uint32_t>(out.positions.size());
    out.positions.emplace_back(CGAL::to_double(p.x()), CGAL::to_double(p.y()),
                               CGAL::to_double(p.z()));
  }
  for (const auto f : surface.faces()) {
    std::array<std::uint32_t, 3> triangle{};
    std::size_t corner = 0;
    for (const auto v : CGAL::vertices_around_face(surface.halfedge(f), surface)) {
      if (corner < 3) triangle[corner] = index[v];
      ++corner;
    }
    if (corner != 3) throw std::runtime_error("a face of the solid is not a triangle");
    out.triangles.push_back(triangle);
  }
  return out;
}

/// True when four of the points are not coplanar (exact predicates): the hull has volume.
bool spans_volume(const std::vector<HullKernel::Point_3>& points) {
  if (points.size() < 4) return false;
  const HullKernel::Point_3& a = points.front();
  std::size_t i = 1;
  while (i < points.size() && points[i] == a) ++i;
  if (i == points.size()) return false;
  const HullKernel::Point_3& b = points[i];
  while (i < points.size() && CGAL::collinear(a, b, points[i])) ++i;
  if (i == points.size()) return false;
  const HullKernel::Point_3& c = points[i];
  while (i < points.size() && CGAL::coplanar(a, b, c, points[i])) ++i;
  return i < points.size();
}

}  // namespace

TriangleMesh union_of_parts(const TriangleMesh& mesh,
                            const std::vector<std::uint32_t>& triangle_part,
                            const std::vector<std::uint32_t>& parts) {
  if (parts.empty()) return {};
  ExactMesh solid = part_surface(mesh, triangle_part, parts.front());
  for (std::size_t i = 1; i < parts.size(); ++i) {
    ExactMesh next = part_surface(mesh, triangle_part, parts[i]);
    ExactMesh merged;
    if (!PMP::corefine_and_compute_union(solid, next, merged)) {
      throw std::runtime_error("the union of part " + std::to_string(parts[i] + 1) +
                               " with the others could not be computed");
    }
    solid = std::move(merged);
  }
  PMP::triangulate_faces(solid);
  return triangle_mesh(solid);
}

TriangleMesh convex_hull_mesh(const std::vector<Eigen::Vector3d>& points,
                              const std::string& source) {
  std::vector<HullKernel::Point_3> input;
  input.reserve(points.size());
  for (const Eigen::Vector3d& p : points) input.emplace_back(p.x(), p.y(), p.z());
  if (!spans_volume(input)) {
    throw InputError(source +
                     ": its points lie in one plane (or on one line), so their convex hull has no "
                     "volume; for a flat part use --inertia shell");
  }
  HullMesh hull;
  CGAL::convex_hull_3(input.begin(), input.end(), hull);
  PMP::triangulate_faces(hull);
  return triangle_mesh(hull);
}

}  // namespace tumble::engine
