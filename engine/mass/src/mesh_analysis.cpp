// From a raw triangle soup to checked mass properties.
//
// Order matters: scale, reject non-finite numbers, weld (STL and OBJ arrive as soups, and
// normals/UV seams split vertices), drop repeated-vertex triangles, then judge the edge
// topology on the welded mesh. Orientation is judged per connected part from signed volumes:
// all parts inside out means the whole file is inverted (flip, warn); an inside-out part that
// lies inside another part is a cavity; one that lies inside nothing is flipped with a warning.
// Containment, crossing and repeated surfaces are decided by exact predicates (part_overlap.hpp).
#include "engine/mass/mesh_analysis.hpp"

#include <algorithm>
#include <cmath>
#include <future>
#include <sstream>
#include <thread>

#include "base/errors.hpp"
#include "engine/geometry/mesh_topology.hpp"
#include "engine/overlap/part_overlap.hpp"
#include "hull_inertia.hpp"
#include "legacy_inertia.hpp"
#include "overlap_policy.hpp"
#include "part_union.hpp"

namespace tumble::engine {
namespace {

std::string format_number(double value) {
  std::ostringstream out;
  out.precision(6);
  out << value;
  return out.str();
}

std::string plural(std::size_t count, const std::string& noun) {
  return std::to_string(count) + " " + noun + (count == 1 ? "" : "s");
}

[[noreturn]] void fail(const std::string& source, const std::string& problem) {
  throw InputError(source + ": " + problem);
}

/// `why`, when known, says what collapsed (a surface cancelling its mirror image).
[[noreturn]] void fail_zero_volume(const std::string& source, const std::string& why = "") {
  fail(source, "encloses zero volume (" + (why.empty() ? "a flat or collapsed surface" : why) +
                   "); for a thin sheet use --shell THICKNESS");
}

void check_options(const MassOptions& options, const std::string& source) {
  const auto positive = [&](const char* name, double value) {
    if (!std::isfinite(value) || value <= 0.0) {
      fail(source,
           std::string(name) + " must be a positive finite number, got " + format_number(value));
    }
  };
  if (options.density && options.mass) fail(source, "give either a density or a mass, not both");
  if (options.density) positive("density", *options.density);
  if (options.mass) positive("mass", *options.mass);
  if (options.shell_thickness) positive("shell thickness", *options.shell_thickness);
  const InertiaMethod method = options.inertia;
  if (options.shell_thickness && method != InertiaMethod::exact && method != InertiaMethod::shell) {
    fail(source, "a shell thickness applies to the shell inertia method, not to " +
                     inertia_method_name(method));
  }
  if (method == InertiaMethod::shell && !options.shell_thickness && !options.mass) {
    fail(source,
         "the shell inertia method needs a thickness (--shell T) or a total mass "
         "(--mass M)");
  }
  for (int axis = 0; axis < 3; ++axis) {
    const double factor = options.scale[axis];
    if (!std::isfinite(factor) || factor == 0.0) {
      fail(source, std::string("scale ") + "xyz"[axis] + " must be a finite non-zero number, got " +
                       format_number(factor));
    }
  }
}

/// Per-part signed volumes, in one pass.
struct PartSummary {
  double signed_volume = 0.0;    // times 6
  double absolute_volume = 0.0;  // sum of |det|, the scale of rounding in signed_volume
  bool reversed = false;
};

std::vector<PartSummary> summarize_parts(const TriangleMesh& mesh, const Topology& topology,
                                         const Eigen::Vector3d& reference) {
  std::vector<PartSummary> parts(topology.parts);
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    const auto& t = mesh.triangles[i];
    PartSummary& part = parts[topology.triangle_part[i]];
    const Eigen::Vector3d a = mesh.positions[t[0]] - reference;
    const Eigen::Vector3d b = mesh.positions[t[1]] - reference;
    const Eigen::Vector3d c = mesh.positions[t[2]] - reference;
    const double det = a.dot(b.cross(c));
    part.signed_volume += det;
    part.absolute_volume += std::abs(det);
  }
  return parts;
}

/// How many layers of matter the other parts put around part `self`: the sum of the exact
/// winding numbers of the parts it lies in (an outer shell +1, a cavity -1), each negated when
/// that part is marked for flipping.
int matter_around(const std::vector<PartSummary>& parts, std::uint32_t self,
                  const std::vector<detail::PartNesting>& nesting) {
  int layers = 0;
  for (const detail::PartNesting& n : nesting) {
    if (n.inner == self) layers += parts[n.outer].reversed ? -n.winding : n.winding;
  }
  return layers;
}

/// Decides which parts to reverse and which are cavities. A negative total means the whole
/// file is inside out (a common export error): everything is reversed first. Then an
/// inward-facing part inside matter is a cavity, one inside nothing is flipped with a warning,
/// and an outward-facing part inside matter overlaps it (counted twice: noted for the policy).
void orient_parts(std::vector<PartSummary>& parts, double signed_total,
                  const std::vector<detail::PartNesting>& nesting, detail::OverlapPolicy& policy,
                  MeshReport& report) {
  if (signed_total < 0.0) {
    for (PartSummary& part : parts) part.reversed = true;
    report.flipped = true;
    report.warnings.push_back("the faces point inward (negative volume): flipped them all");
  }
  if (parts.size() < 2) return;
  const auto inward = [&](std::uint32_t i) {
    return (parts[i].signed_volume < 0.0) != parts[i].reversed;
  };
  const auto count = static_cast<std::uint32_t>(parts.size());
  const std::string of = " of " + std::to_string(count);

  // Inward-facing parts first: cavities stay, lone ones are flipped.
  for (std::uint32_t i = 0; i < count; ++i) {
    if (!inward(i)) continue;
    if (matter_around(parts, i, nesting) > 0) {
      ++report.cavities;
    } else {
      parts[i].reversed = !parts[i].reversed;
      report.warnings.push_back("part " + std::to_string(i + 1) + of +
                                " points inward but lies inside no other part: flipped it");
    }
  }
  // Then outward-facing parts that sit in matter.
  for (std::uint32_t i = 0; i < count; ++i) {
    if (inward(i) || matter_around(parts, i, nesting) <= 0) continue;
    std::vector<std::uint32_t> outers;  // the outward parts around it (for their union)
    for (const detail::PartNesting& n : nesting) {
      if (n.inner == i && !inward(n.outer)) outers.push_back(n.outer);
    }
    policy.nested(i, std::abs(parts[i].signed_volume) / 6.0, outers);
  }
}

void flip_reversed_parts(TriangleMesh& mesh, const Topology& topology,
                         const std::vector<PartSummary>& parts) {
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    if (parts[topology.triangle_part[i]].reversed)
      std::swap(mesh.triangles[i][1], mesh.triangles[i][2]);
  }
}

/// Scales to metres and rejects non-finite coordinates (also those that overflow on scaling). A
/// mirroring scale (negative product) reverses every triangle, so outward stays outward.
void scale_positions(TriangleMesh& mesh, const Eigen::Vector3d& scale, const std::string& source) {
  const bool scaled = scale != Eigen::Vector3d::Ones();
  if (scale.prod() < 0.0) {
    for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
  }
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    Eigen::Vector3d& p = mesh.positions[i];
    if (scaled) p = p.cwiseProduct(scale);
    if (!p.allFinite()) {
      fail(source, "vertex " + std::to_string(i + 1) + " has a non-finite coordinate");
    }
  }
}

/// Welds, then drops triangles that use a vertex twice and vertices no triangle uses (they are
/// not part of the body, and would move the bounding box).
void weld_and_clean(TriangleMesh& mesh, bool distinct_positions, MeshReport& report) {
  if (!distinct_positions) report.welded_vertices = weld_by_position(mesh);
  report.degenerate_triangles = remove_degenerate_triangles(mesh);
  remove_unreferenced_vertices(mesh);
  report.vertices = mesh.positions.size();
  report.triangles = mesh.triangles.size();
  if (mesh.triangles.empty()) {
    fail(report.source, "all " + plural(report.input_triangles, "triangle") + " are degenerate");
  }
  if (report.degenerate_triangles > 0) {
    report.warnings.push_back("skipped " +
                              plural(report.degenerate_triangles, "degenerate triangle"));
  }
}

/// The bounding box into the report; its centre (returned) is the reference point of all
/// integrals.
Eigen::Vector3d bound(const TriangleMesh& mesh, MeshReport& report) {
  report.bounds_min = report.bounds_max = mesh.positions.front();
  for (const Eigen::Vector3d& p : mesh.positions) {
    report.bounds_min = report.bounds_min.cwiseMin(p);
    report.bounds_max = report.bounds_max.cwiseMax(p);
  }
  return 0.5 * (report.bounds_min + report.bounds_max);
}

/// The topology of the mesh, and its volume integrals when they were summed alongside.
struct TopologyPass {
  Topology topology;
  MomentIntegrals solid;
  bool concurrent = false;  ///< `solid` holds the integrals of the mesh as read
};

/// Edge topology and connected parts, into the report. On large meshes the edge counts (the
/// longest pass) run on a second thread, while this one sums the volume integrals (needed in
/// the common single-part case) and then finds the parts.
TopologyPass check_topology(const TriangleMesh& mesh, const Eigen::Vector3d& reference,
                            MeshReport& report) {
  TopologyPass pass;
  pass.concurrent = !report.shell && mesh.triangles.size() >= 200'000;
  Topology& topology = pass.topology;
  if (pass.concurrent) {
    std::future<void> edges =
        std::async(std::launch::async, [&mesh, &topology] { count_edge_uses(mesh, topology); });
    pass.solid = solid_integrals(mesh, reference);
    find_parts(mesh, topology);
    edges.get();
  } else {
    topology = analyze_topology(mesh);
  }
  report.parts = topology.parts;
  report.boundary_edges = topology.boundary_edges;
  report.inconsistent_edges = topology.inconsistent_edges;
  report.non_manifold_edges = topology.non_manifold_edges;
  report.watertight = topology.closed();
  const std::size_t paired = topology.non_manifold_edges - topology.unpaired_non_manifold_edges;
  if (paired > 0 && topology.closed()) {
    report.warnings.push_back(plural(paired, "edge") +
                              " shared by more than two triangles (closed, but not a manifold)");
  }
  return pass;
}

/// Thin shell: area-weighted, orientation and closure do not matter. Without a thickness the
/// mass alone gives the areal density (mass / area); volume and density are then not known (0).
void shell_properties(const TriangleMesh& mesh, const Eigen::Vector3d& reference,
                      const MassOptions& options, MeshReport& report) {
  const MomentIntegrals integrals = surface_integrals(mesh, reference);
  report.method = InertiaMethod::shell;
  report.area = integrals.measure;
  if (!(report.area > 0.0)) fail(report.source, "has zero surface area");
  if (options.shell_thickness) {
    report.thickness = *options.shell_thickness;
    report.volume = report.area * report.thickness;
    report.density =
        options.mass ? *options.mass / report.volume : options.density.value_or(1000.0);
    report.areal_density = report.density * report.thickness;
  } else {
    report.areal_density = *options.mass / report.area;
  }
  // The areal density (rho * t) turns area integrals into mass integrals.
  report.mass_properties = mass_properties(integrals, reference, report.areal_density);
}

/// A closed surface must have no boundary, pair up the uses of every edge shared by more than
/// two triangles, and have a consistent winding.
void require_closed_and_consistent(const Topology& topology, const std::string& source) {
  if (topology.boundary_edges > 0) {
    fail(source, "the surface is open (" + plural(topology.boundary_edges, "boundary edge") +
                     "), so it encloses no volume; for a thin sheet or open surface use "
                     "--shell THICKNESS");
  }
  if (topology.unpaired_non_manifold_edges > 0) {
    fail(source, "not a manifold: " + plural(topology.unpaired_non_manifold_edges, "edge") +
                     " shared by three or more triangles whose directions do not pair up (as "
                     "many one way as the other), so the surface does not bound a volume");
  }
  if (topology.inconsistent_edges > 0) {
    fail(source, "inconsistent winding: " + plural(topology.inconsistent_edges, "edge") +
                     " used twice in the same direction (neighbouring faces disagree on "
                     "inside and outside)");
  }
}

/// One part: its orientation is the sign of the volume; flipping every face negates all three
/// integrals, so no second pass is needed.
MomentIntegrals single_part_integrals(const TriangleMesh& mesh, const Eigen::Vector3d& reference,
                                      TopologyPass& pass, const std::string& cancelled,
                                      MeshReport& report) {
  MomentIntegrals solid = pass.concurrent ? pass.solid : solid_integrals(mesh, reference);
  if (!(std::abs(solid.measure) > 1e-9 * solid.absolute_measure)) {
    fail_zero_volume(report.source, cancelled);
  }
  if (solid.measure < 0.0) {
    solid.measure = -solid.measure;
    solid.first = -solid.first;
    solid.second = -solid.second;
    report.flipped = true;
    report.warnings.push_back("the faces point inward (negative volume): flipped them all");
  }
  return solid;
}

/// Several parts: each oriented (cavities, lone inward parts flipped), then integrated again
/// when some part was flipped or the integrals were not summed yet.
MomentIntegrals multi_part_integrals(TriangleMesh& mesh, const Eigen::Vector3d& reference,
                                     const TopologyPass& pass,
                                     const std::vector<detail::PartNesting>& nesting,
                                     detail::OverlapPolicy& policy, MeshReport& report) {
  std::vector<PartSummary> parts = summarize_parts(mesh, pass.topology, reference);
  double signed_total = 0.0, absolute_total = 0.0;
  for (const PartSummary& part : parts) {
    signed_total += part.signed_volume;
    absolute_total += part.absolute_volume;
  }
  // Zero volume relative to the rounding scale of the signed sum (scale-free).
  if (!(std::abs(signed_total) > 1e-9 * absolute_total)) {
    fail_zero_volume(report.source, policy.cancelled());
  }
  orient_parts(parts, signed_total, nesting, policy, report);
  policy.settle(report);
  const bool any_reversed =
      std::any_of(parts.begin(), parts.end(), [](const PartSummary& p) { return p.reversed; });
  if (any_reversed) flip_reversed_parts(mesh, pass.topology, parts);
  return (any_reversed || !pass.concurrent) ? solid_integrals(mesh, reference) : pass.solid;
}

/// Solid body: closed, consistently wound, every part oriented, positive volume.
void solid_properties(TriangleMesh& mesh, const Eigen::Vector3d& reference,
                      const MassOptions& options, TopologyPass& pass, MeshReport& report) {
  require_closed_and_consistent(pass.topology, report.source);
  // Exact tests for parts that cross, nest, repeat or intersect themselves: an error unless
  // allowed (overlap_policy.hpp).
  detail::OverlapOptions search;
  search.threads =
      options.jobs != 0 ? options.jobs : std::max(1u, std::thread::hardware_concurrency());
  search.face_pairs = options.check_overlap;
  search.bounds.emplace(report.bounds_min, report.bounds_max);  // bound() found them
  const detail::PartOverlaps overlaps =
      detail::find_part_overlaps(mesh, pass.topology.triangle_part, pass.topology.parts, search);
  detail::OverlapPolicy policy(options.overlap, report.source, pass.topology.parts);
  report.overlap = options.overlap;
  policy.findings(overlaps);
  policy.settle(report);
  MomentIntegrals integrals =
      pass.topology.parts == 1
          ? single_part_integrals(mesh, reference, pass, policy.cancelled(), report)
          : multi_part_integrals(mesh, reference, pass, overlaps.nesting, policy, report);
  if (options.overlap == OverlapMode::kUnion && !policy.united().empty()) {
    // A single part flipped as a whole kept its faces: turn them outward for the union.
    if (pass.topology.parts == 1 && report.flipped) {
      for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
    }
    integrals = detail::united_integrals(mesh, pass.topology, policy.united(), reference, report);
  }
  report.volume = integrals.measure;
  if (!(report.volume > 0.0)) {
    fail(report.source, "encloses a non-positive volume (" + format_number(report.volume) +
                            " m^3) once cavities are taken out");
  }
  report.density = options.mass ? *options.mass / report.volume : options.density.value_or(1000.0);
  report.mass_properties = mass_properties(integrals, reference, report.density);
}

/// The solid the mesh encloses, when exact accepts it (closed, consistent, no refused
/// overlap): the convex method states the hull's volume beside it. The mesh is not changed.
std::optional<double> enclosed_volume(const TriangleMesh& mesh, const Eigen::Vector3d& reference,
                                      const MassOptions& options, TopologyPass& pass,
                                      const MeshReport& report) {
  const Topology& topology = pass.topology;
  if (!topology.closed() || topology.inconsistent_edges > 0) return std::nullopt;
  TriangleMesh copy = mesh;
  MeshReport trial = report;
  try {
    solid_properties(copy, reference, options, pass, trial);
  } catch (const InputError&) {
    return std::nullopt;
  }
  return trial.volume;
}

/// The reason in an InputError's message, without the leading "SOURCE: ".
std::string refusal_reason(const InputError& error, const std::string& source) {
  const std::string message = error.what();
  const std::string prefix = source + ": ";
  return message.rfind(prefix, 0) == 0 ? message.substr(prefix.size()) : message;
}

/// Exact; where exact refuses the mesh, the convex hull, with a warning naming the reason.
void exact_or_convex(TriangleMesh& mesh, const Eigen::Vector3d& reference,
                     const MassOptions& options, TopologyPass& pass, MeshReport& report) {
  const MeshReport before = report;
  try {
    solid_properties(mesh, reference, options, pass, report);
    return;
  } catch (const InputError& error) {
    report = before;
    report.fallback_reason = refusal_reason(error, report.source);
  }
  report.warnings.push_back("exact inertia refused (" + *report.fallback_reason +
                            "): used the convex hull's solid instead");
  detail::convex_properties(mesh, reference, options, std::nullopt, report);
}

}  // namespace

const char* overlap_mode_name(OverlapMode mode) {
  switch (mode) {
    case OverlapMode::kSum:
      return "sum";
    case OverlapMode::kRefuse:
      return "refuse";
    case OverlapMode::kUnion:
      break;
  }
  return "union";
}

std::optional<OverlapMode> overlap_mode_named(std::string_view name) {
  for (const OverlapMode mode : {OverlapMode::kUnion, OverlapMode::kSum, OverlapMode::kRefuse}) {
    if (name == overlap_mode_name(mode)) return mode;
  }
  return std::nullopt;
}

MeshReport analyze_mesh(TriangleMesh mesh, const MassOptions& options, const std::string& source,
                        bool distinct_positions) {
  check_options(options, source);
  MeshReport report;
  report.source = source;
  report.input_triangles = mesh.triangles.size();
  const InertiaMethod method = options.shell_thickness ? InertiaMethod::shell : options.inertia;
  report.shell = method == InertiaMethod::shell;
  if (mesh.triangles.empty()) fail(source, "contains no triangles");

  scale_positions(mesh, options.scale, source);                 // metres, finite
  weld_and_clean(mesh, distinct_positions, report);             // welded, no degenerate triangles
  const Eigen::Vector3d reference = bound(mesh, report);        // bounding-box centre
  TopologyPass pass = check_topology(mesh, reference, report);  // edges and parts
  switch (method) {
    case InertiaMethod::shell:
      shell_properties(mesh, reference, options, report);
      break;
    case InertiaMethod::convex:
      detail::convex_properties(mesh, reference, options,
                                enclosed_volume(mesh, reference, options, pass, report), report);
      break;
    case InertiaMethod::legacy:
      detail::legacy_properties(mesh, options,
                                enclosed_volume(mesh, reference, options, pass, report), report);
      break;
    case InertiaMethod::automatic:
      exact_or_convex(mesh, reference, options, pass, report);
      break;
    case InertiaMethod::exact:
      solid_properties(mesh, reference, options, pass, report);
      break;
  }

  // Principal frame, and the checks any rigid body must pass.
  report.principal = principal_frame(report.mass_properties.inertia);
  if (const auto problem = principal_moments_problem(report.principal.moments)) {
    fail(source, *problem);
  }
  return report;
}

}  // namespace tumble::engine
