// The convex method. The hull is built by CGAL's quickhull with exact predicates
// (engine/overlap/solids.hpp), so it exists for any vertex set spanning a volume: open,
// non-manifold or self-intersecting surfaces alike, as long as the points are not all in one
// plane. Its faces are outward-wound triangles, so the ordinary volume integrals (Mirtich 1996,
// as mass_properties.hpp) give its solid's mass properties.
#include "hull_inertia.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include "engine/mass/mass_properties.hpp"
#include "engine/overlap/solids.hpp"

namespace tumble::engine::detail {
namespace {

/// Above this relative difference between the hull's volume and the enclosed one, the hull is
/// a poor stand-in for the part (a concave shape) and a warning says so.
constexpr double kHullVolumeTolerance = 0.05;

std::string hull_number(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

}  // namespace

void convex_properties(const TriangleMesh& mesh, const Eigen::Vector3d& reference,
                       const MassOptions& options, std::optional<double> enclosed_volume,
                       MeshReport& report) {
  const TriangleMesh hull = convex_hull_mesh(mesh.positions, report.source);
  const MomentIntegrals integrals = solid_integrals(hull, reference);
  report.method = InertiaMethod::convex;
  report.volume = integrals.measure;
  report.hull_volume = integrals.measure;
  report.hull_triangles = hull.triangles.size();
  report.enclosed_volume = enclosed_volume;
  report.density = options.mass ? *options.mass / report.volume : options.density.value_or(1000.0);
  report.mass_properties = mass_properties(integrals, reference, report.density);
  if (enclosed_volume && *enclosed_volume > 0.0) {
    const double excess = (report.volume - *enclosed_volume) / *enclosed_volume;
    if (std::abs(excess) > kHullVolumeTolerance) {
      report.warnings.push_back(
          "the convex hull's volume (" + hull_number(report.volume) + " m^3) is " +
          hull_number(100.0 * excess) + "% more than the volume the mesh encloses (" +
          hull_number(*enclosed_volume) + " m^3): the hull badly approximates a concave part");
    }
  }
}

}  // namespace tumble::engine::detail
