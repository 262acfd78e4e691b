#pragma once
/// @file From a raw triangle soup to checked mass properties: the `tumble inspect` pipeline.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "engine/geometry/triangle_mesh.hpp"
#include "engine/mass/inertia_method.hpp"
#include "engine/mass/mass_properties.hpp"
#include "engine/mass/principal_frame.hpp"

namespace tumble::engine {

/// What to do with parts that overlap, nest with the same orientation or repeat.
enum class OverlapMode {
  kUnion,   ///< the solid is their exact union (CGAL corefinement); a warning states the shared
            ///< volume (the default)
  kSum,     ///< each part counts whole: the shared volume counts twice (a warning says how much)
  kRefuse,  ///< an error naming the parts
};

/// "union", "sum" or "refuse".
const char* overlap_mode_name(OverlapMode mode);
/// The mode named "union", "sum" or "refuse"; nullopt for any other text.
std::optional<OverlapMode> overlap_mode_named(std::string_view name);

/// How to turn a mesh's geometry into matter.
struct MassOptions {
  std::optional<double> density;  ///< kg/m^3; the default is 1000 (water)
  std::optional<double> mass;     ///< kg, total; excludes `density`
  /// File units to metres per axis (0.001 for millimetres), as URDF's <mesh scale="x y z">.
  /// Each factor is finite and non-zero; a negative one mirrors along its axis, and when the
  /// product is negative the winding is reversed so the faces still point outward.
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  std::optional<double> shell_thickness;  ///< m; thin-shell (area-weighted) mode when set
  /// Parts that overlap or repeat: their union (default), their sum, or an error. A part that
  /// intersects itself is counted as wound with kSum and refused otherwise (the exact union
  /// needs parts free of self-intersections).
  OverlapMode overlap = OverlapMode::kUnion;
  /// How the geometry becomes inertia; a shell thickness alone implies InertiaMethod::shell.
  /// The shell method needs `shell_thickness` or `mass` (then the areal density is mass/area).
  InertiaMethod inertia = InertiaMethod::exact;
  /// Test the parts for self-intersections, repeated faces and crossings (exact; the default).
  /// Off, none of them is found: self-intersections and repeats count without a warning, and
  /// parts that cross may be taken as nested; whether a part lies inside another (a cavity, or
  /// matter counted twice) is still decided.
  bool check_overlap = true;
  /// Threads for those tests; 0: one per core.
  unsigned jobs = 0;
};

/// Everything `tumble inspect` reports about one mesh, in SI units after scaling.
struct MeshReport {
  std::string source;
  std::size_t input_triangles = 0;       ///< as read
  std::size_t triangles = 0;             ///< used (degenerate ones skipped)
  std::size_t vertices = 0;              ///< after welding
  std::size_t welded_vertices = 0;       ///< merged away by welding
  std::size_t degenerate_triangles = 0;  ///< skipped
  std::size_t parts = 0;
  std::size_t cavities = 0;  ///< inward-facing parts inside another part
  std::size_t boundary_edges = 0;
  std::size_t inconsistent_edges = 0;
  std::size_t non_manifold_edges = 0;
  bool watertight = false;
  bool shell = false;
  /// The method that gave the mass properties: exact, convex, shell or legacy (never automatic).
  InertiaMethod method = InertiaMethod::exact;
  /// Why exact was refused when InertiaMethod::automatic fell back to convex.
  std::optional<std::string> fallback_reason;
  std::optional<double> enclosed_volume;  ///< m^3 (convex, legacy: the exact solid, if any)
  double hull_volume = 0.0;               ///< m^3 (convex only)
  std::size_t hull_triangles = 0;         ///< convex only
  double areal_density = 0.0;             ///< kg/m^2 (shell mode)
  bool flipped = false;                   ///< all faces were inverted and have been flipped
  double thickness = 0.0;                 ///< m (shell mode; 0 when given by mass alone)
  double volume = 0.0;                    ///< m^3 (shell mode: area times thickness; convex: hull)
  double area = 0.0;                      ///< m^2 (shell mode only)
  double density = 0.0;                   ///< kg/m^3
  MassProperties mass_properties;         ///< inertia about the centre of mass, file axes
  PrincipalFrame principal;
  Eigen::Vector3d bounds_min = Eigen::Vector3d::Zero();
  Eigen::Vector3d bounds_max = Eigen::Vector3d::Zero();
  std::vector<std::string> warnings;          ///< things the user should know and may want to fix
  OverlapMode overlap = OverlapMode::kUnion;  ///< the mode the mass properties were computed in
  std::size_t united_parts = 0;  ///< parts replaced by their exact union (kUnion), 0 if none
  double shared_volume = 0.0;    ///< m^3: their volumes' sum minus their union's
};

/// Validates options, scales, welds, checks and integrates `mesh`. Throws InputError with a
/// one-line message starting with `source` on anything that is not a valid rigid body.
/// `distinct_positions` says the caller knows no two vertices share a position (as
/// import_mesh reports for single-mesh files), which skips the weld.
MeshReport analyze_mesh(TriangleMesh mesh, const MassOptions& options, const std::string& source,
                        bool distinct_positions = false);

}  // namespace tumble::engine
