#pragma once
/// @file Scene files: JSON in, a plain checked description out, then bodies for the engine.
///
/// Two stages, kept apart so each is testable alone:
///  - parse_scene() reads and validates the JSON into a SceneDescription (no meshes are read:
///    only values the file holds are checked);
///  - compile_scene() imports meshes, computes mass properties, moves everything to the
///    principal frame about each body's rotation centre and returns engine bodies and states.
///
/// Every error is an tumble::InputError whose one-line message starts with the scene file and
/// the JSON path of the offending value (`scene.json: bodies[0].angular_velocity: ...`) and
/// says what was expected. The format is documented at parse_scene().

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "engine/body/rigid_body.hpp"
#include "engine/geometry/triangle_mesh.hpp"
#include "engine/mass/mesh_analysis.hpp"
#include "engine/mass/primitive_shapes.hpp"
#include "engine/simulation/simulation.hpp"

namespace tumble::app {

/// The frame a vector in the scene file is written in.
enum class VectorFrame { kWorld, kBody };

/// A spring from a world anchor to a body point (body frame, relative to the centre of mass).
struct SpringDescription {
  Eigen::Vector3d anchor = Eigen::Vector3d::Zero();  ///< world, m
  Eigen::Vector3d attach = Eigen::Vector3d::Zero();  ///< body frame, m
  double stiffness = 0.0;                            ///< N/m
  double damping = 0.0;                              ///< N s/m
};

/// One body as the scene file describes it. Exactly one of `mesh`, `shape`,
/// `principal_moments`, `inertia_tensor` is set; with a mesh or a shape exactly one of `mass`,
/// `density`, with an inertia `mass`.
struct BodyDescription {
  std::string name;
  std::optional<std::filesystem::path> mesh;         ///< resolved against the scene's folder
  std::optional<engine::Shape> shape;                ///< a primitive solid, validated
  std::optional<Eigen::Vector3d> principal_moments;  ///< kg m^2, about the centre of mass
  std::optional<Eigen::Matrix3d> inertia_tensor;     ///< kg m^2, about the centre of mass
  std::optional<double> mass;                        ///< kg
  std::optional<double> density;                     ///< kg/m^3 (mesh or shape only)
  double scale = 1.0;                                ///< mesh units to metres (mesh only)
  /// Overlapping parts of the mesh: their union (default), sum or an error (MassOptions).
  engine::OverlapMode overlap = engine::OverlapMode::kUnion;
  /// How the mesh becomes inertia ("inertia_method"; shell needs "mass": mass over area).
  engine::InertiaMethod inertia_method = engine::InertiaMethod::exact;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();               ///< centre of mass, world, m
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  ///< body to world, unit
  std::optional<Eigen::Vector3d> velocity;  ///< of the centre of mass (free bodies)
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();  ///< rad/s
  VectorFrame angular_velocity_frame = VectorFrame::kWorld;
  std::optional<Eigen::Vector3d> pivot;   ///< body frame point fixed in the world
  std::optional<Eigen::Vector3d> torque;  ///< N m
  VectorFrame torque_frame = VectorFrame::kWorld;
  std::optional<SpringDescription> spring;
};

/// A whole scene file after validation (no mesh read yet).
struct SceneDescription {
  std::filesystem::path file;  ///< as given (used in messages)
  std::string name;
  double duration = 0.0;                     ///< s
  double dt = 0.0;                           ///< s
  std::string integrator = "rk4";            ///< a name from engine::integrator_catalog()
  std::optional<double> tolerance;           ///< adaptive integrators: relative tolerance
  std::optional<double> absolute_tolerance;  ///< adaptive integrators: absolute tolerance
  std::optional<Eigen::Vector3d> gravity;    ///< m/s^2, world
  std::vector<BodyDescription> bodies;
  /// The scene's `render` object, kept as written for parse_render_settings (absent: defaults).
  std::optional<nlohmann::json> render;
};

/// Parses and validates scene JSON text. `file` names the source in messages and anchors
/// relative mesh paths. JSON may carry // and /* */ comments. Throws tumble::InputError.
///
/// Top level: "duration", "dt" (required, positive, finite, dt <= duration), "bodies"
/// (required, non-empty array); optional "name" (default: the file's stem), "integrator"
/// (default "rk4"), "tolerance" (positive: the relative tolerance rtol of adaptive
/// integrators), "absolute_tolerance" (>= 0: their absolute tolerance atol, in each quantity's
/// SI unit; engine/PHYSICS.md §3), "gravity" ([x, y, z]; absent: no gravity).
/// Body: "name" (default "body<i>", unique, non-empty); exactly one of "mesh" (path),
/// "shape" (a primitive solid, app/scene/shape_field.hpp) and "inertia" ({"principal":
/// [I1, I2, I3]} or {"tensor": [[..], [..], [..]]}); with a mesh or a shape exactly one of
/// "mass" and "density", with an inertia "mass"; "scale" (mesh only, positive);
/// "overlap" (mesh only: "union" (default), "sum" or "refuse", engine::OverlapMode) or its old
/// alias "allow_overlap" (mesh only, boolean: true is "sum", false "refuse");
/// "inertia_method" (mesh only: "exact", "convex", "shell", "legacy" or "auto", as inspect
/// --inertia); "position", "orientation" ([w, x, y, z], any non-zero quaternion, normalised),
/// "velocity" (not with "pivot"), "angular_velocity", "angular_velocity_frame" ("world" by
/// default or "body"), "pivot", "torque", "torque_frame", "spring" ({"anchor", "attach",
/// "stiffness", "damping" (default 0)}). Unknown keys are errors.
SceneDescription parse_scene(const std::string& text, const std::filesystem::path& file);

/// The files a run of `scene` reads: the scene file and its meshes. No output may be one of
/// them (tumble/file_checks.hpp refuses it).
std::vector<std::filesystem::path> scene_inputs(const SceneDescription& scene);

/// The most steps a run may take (a bound on duration / dt; keeps step counts exact).
inline constexpr double kMaxSteps = 1e12;

/// What is wrong with a time step `dt` for `duration` (both positive and finite): longer than
/// the duration, or more than kMaxSteps steps. Nothing when it is fine.
std::optional<std::string> step_problem(double dt, double duration);

/// The integrator names, comma-separated, for messages.
std::string integrator_names();

/// Command-line overrides shared by the commands. Each throws tumble::InputError naming the
/// option: `--integrator` must name a known integrator; numbers must be positive and finite.
void override_integrator(SceneDescription& scene, const std::string& name);
double positive_option(double value, const char* option);

/// Reads `file` and parses it (see parse_scene).
SceneDescription load_scene(const std::filesystem::path& file);

/// Bodies and settings ready for engine::Simulation.
struct CompiledScene {
  std::vector<engine::BodyModel> bodies;
  std::vector<engine::BodyState> initial;
  engine::SimulationSettings settings;
  std::size_t meshes_imported = 0;  ///< mesh files read (0 when every inertia is given)
  /// Per body, its mesh in the body frame (the file's axes moved to the centre of mass,
  /// metres), when the body has a mesh, or its shape's tessellation (kShapeSegments) when it
  /// has a shape; kept only when compile_scene is asked for it.
  std::vector<std::optional<engine::TriangleMesh>> geometry;
  /// Per body, the mass-property report of its mesh (what `tumble inspect` prints), when it
  /// has one.
  std::vector<std::optional<engine::MeshReport>> reports;
};

/// Segments about the axis of a shape body's drawn tessellation (engine::tessellate).
inline constexpr int kShapeSegments = 64;

/// Imports meshes, computes mass properties about each rotation centre and builds the initial
/// states. Mesh errors come back with the body's JSON path in front. Throws tumble::InputError.
/// With `keep_geometry`, the meshes are kept for drawing (see CompiledScene::geometry).
CompiledScene compile_scene(const SceneDescription& scene, bool keep_geometry = false);

/// The simulation settings of a scene (integrator, dt, duration, tolerance): what
/// compile_scene puts in CompiledScene::settings, for runs of one compiled scene that differ
/// only there.
engine::SimulationSettings simulation_settings(const SceneDescription& scene);

}  // namespace tumble::app
