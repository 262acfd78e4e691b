// The exact union of overlapping parts, integrated (part_union.hpp).
#include "part_union.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <exception>
#include <sstream>
#include <string>

#include "base/errors.hpp"
#include "engine/overlap/solids.hpp"

namespace tumble::engine::detail {
namespace {

/// The triangles of `mesh` whose part is (`keep` true) or is not in the sorted `parts`; the
/// positions are shared (the integrals only visit the triangles' vertices).
TriangleMesh union_submesh(const TriangleMesh& mesh, const Topology& topology,
                           const std::vector<std::uint32_t>& parts, bool keep) {
  TriangleMesh out;
  out.positions = mesh.positions;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const bool listed = std::binary_search(parts.begin(), parts.end(), topology.triangle_part[t]);
    if (listed == keep) out.triangles.push_back(mesh.triangles[t]);
  }
  return out;
}

MomentIntegrals union_plus(const MomentIntegrals& a, const MomentIntegrals& b) {
  MomentIntegrals sum;
  sum.measure = a.measure + b.measure;
  sum.absolute_measure = a.absolute_measure + b.absolute_measure;
  sum.first = a.first + b.first;
  sum.second = a.second + b.second;
  return sum;
}

std::string union_number(double value) {
  std::ostringstream out;
  out.precision(6);
  out << value;
  return out.str();
}

std::string union_part_list(const std::vector<std::uint32_t>& parts, std::size_t count) {
  std::string text = parts.size() == 1 ? "part " : "parts ";
  for (std::size_t i = 0; i < parts.size(); ++i) {
    if (i > 0) text += i + 1 == parts.size() ? " and " : ", ";
    text += std::to_string(parts[i] + 1);
  }
  return text + " of " + std::to_string(count);
}

/// The union's triangles in an order of their own (each rotated to start at its least corner,
/// then sorted by corners), so that the integrals summed over them do not depend on the order in
/// which the corefinement returned them.
void canonical_order(TriangleMesh& solid) {
  using Corners = std::array<Eigen::Vector3d, 3>;
  const auto less = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  };
  std::vector<Corners> triangles;
  triangles.reserve(solid.triangles.size());
  for (const auto& t : solid.triangles) {
    Corners c{solid.positions[t[0]], solid.positions[t[1]], solid.positions[t[2]]};
    const std::size_t first =
        static_cast<std::size_t>(std::min_element(c.begin(), c.end(), less) - c.begin());
    std::rotate(c.begin(), c.begin() + static_cast<std::ptrdiff_t>(first), c.end());
    triangles.push_back(c);
  }
  std::sort(triangles.begin(), triangles.end(), [&](const Corners& a, const Corners& b) {
    return std::lexicographical_compare(a.begin(), a.end(), b.begin(), b.end(), less);
  });
  solid.positions.clear();
  solid.triangles.clear();
  for (const Corners& c : triangles) {
    const auto base = static_cast<std::uint32_t>(solid.positions.size());
    solid.positions.insert(solid.positions.end(), c.begin(), c.end());
    solid.triangles.push_back({base, base + 1, base + 2});
  }
}

}  // namespace

MomentIntegrals united_integrals(const TriangleMesh& mesh, const Topology& topology,
                                 const std::vector<std::uint32_t>& united,
                                 const Eigen::Vector3d& reference, MeshReport& report) {
  const MomentIntegrals rest =
      solid_integrals(union_submesh(mesh, topology, united, false), reference);
  const MomentIntegrals summed =
      solid_integrals(union_submesh(mesh, topology, united, true), reference);
  TriangleMesh solid;
  try {
    solid = union_of_parts(mesh, topology.triangle_part, united);
  } catch (const std::exception& error) {
    throw InputError(report.source + ": the exact union of its overlapping " +
                     union_part_list(united, topology.parts) + " could not be computed (" +
                     error.what() + "); give --overlap sum to count each part whole");
  }
  canonical_order(solid);
  const MomentIntegrals merged = solid_integrals(solid, reference);
  const MomentIntegrals total = union_plus(rest, merged);
  report.united_parts = united.size();
  report.shared_volume = std::max(0.0, summed.measure - merged.measure);
  const double fraction = total.measure > 0.0 ? report.shared_volume / total.measure : 0.0;
  const bool one = united.size() == 1;  // a part that repeats its faces
  report.warnings.push_back(union_part_list(united, topology.parts) +
                            (one ? " is taken once (--overlap union): its repeated volume, "
                                   "counted once, is "
                                 : " are taken as their exact union (--overlap union): their "
                                   "shared volume, counted once, is ") +
                            union_number(report.shared_volume) + " m^3 (" +
                            union_number(100.0 * fraction) + "% of the mesh's volume)");
  return total;
}

}  // namespace tumble::engine::detail
