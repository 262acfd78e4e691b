#pragma once
/// @file A robot description (URDF, SDF or MJCF) as `tumble inertials` sees it: for each link
/// (URDF, SDF) or body (MJCF), the geometry its inertial follows from and the inertial the file
/// states now, with where in the file's bytes that element is (to replace it, and nothing else).

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include <Eigen/Geometry>

#include "engine/mass/inertia_method.hpp"
#include "engine/mass/mass_properties.hpp"
#include "engine/mass/primitive_shapes.hpp"

namespace tumble::app::robot {

enum class RobotFormat { urdf, sdf, mjcf };

/// Which of a link's geometries give its shape: `collision` (the default) or `visual`.
/// In MJCF a geom is both; `collision` takes geoms that collide (contype or conaffinity
/// non-zero, MuJoCo's default) and `visual` those that do not (group-only decoration),
/// falling back to all geoms of a body when none is of the kind asked for.
enum class GeometrySource { collision, visual };

/// A mesh file as a geometry: the resolved path and the scale per axis (a negative factor
/// mirrors; the winding is then reversed so the volume stays positive).
struct MeshGeometry {
  std::filesystem::path file;
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  /// MJCF only: the method the file asks for (<mesh inertia=...>, shellinertia, or the
  /// compiler's); it overrides ComputeOptions::inertia. Shell: the density is per area, as
  /// MuJoCo reads it.
  std::optional<engine::InertiaMethod> inertia;
};

/// One geometry of a link.
struct Geometry {
  std::variant<engine::Shape, MeshGeometry> shape;
  /// The geometry's frame in the link's frame (URDF origin, SDF pose, MJCF pos/quat/...).
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  /// Where it is, for messages: "link 'arm' collision 1", "body 'hand' geom 'palm'".
  std::string where;
  /// The geometry's own density (MJCF geom density, SDF <collision><density>) or mass (MJCF
  /// geom mass), when the file gives one.
  std::optional<double> density;
  std::optional<double> mass;
};

/// An inertial element of the file, as written: any of its values may be missing.
struct StatedInertial {
  std::optional<double> mass;                                ///< kg
  Eigen::Vector3d center_of_mass = Eigen::Vector3d::Zero();  ///< link frame (m)
  /// About the centre of mass, in the link's axes (the element's own rotation applied).
  std::optional<Eigen::Matrix3d> inertia;
};

/// A byte range [begin, end) of the file's text.
struct ByteRange {
  std::size_t begin = 0;
  std::size_t end = 0;
};

/// One link (URDF, SDF) or body (MJCF).
struct Link {
  std::string name;
  /// The link's frame in the model's frame in the zero configuration (every joint at zero):
  /// URDF, the chain of joint origins from the root; SDF, the link's pose; MJCF, the nested
  /// bodies' pos/quat. Identity for a root link.
  Eigen::Isometry3d frame = Eigen::Isometry3d::Identity();
  /// The parent link's name (URDF/SDF: the joint whose child it is; MJCF: the enclosing body);
  /// empty for a root.
  std::string parent;
  std::vector<Geometry> geometries;
  /// The inertial the file states, if it has an inertial element (unset for SDF's
  /// <inertial auto="true">, whose values are not used).
  std::optional<StatedInertial> stated;
  /// SDF <inertial auto="true"> (SDFormat 1.11): the inertial is the one computed from the
  /// collisions, each at its own density, whatever values the element states.
  bool auto_inertial = false;
  /// Where the inertial element is in the file's text, from its '<' to the end of its closing
  /// tag (or of "/>"); unset when the link has none.
  std::optional<ByteRange> inertial_bytes;
  /// Where a new inertial element goes when the link has none: the offset just after the
  /// link's start tag (a self-closing `<link .../>` cannot take one: then unset, and `-o`
  /// reports the link), and the indentation of the link's children ("    ").
  std::optional<std::size_t> insert_at;
  std::string child_indent;
  /// Things the user should know about this link (a geometry kind tumble ignores, such as a
  /// plane or a height field), one sentence each.
  std::vector<std::string> notes;
};

/// Where `package://NAME/...` paths lead: NAME to its folder. Filled from
/// `--package-path NAME=DIR` and ROS_PACKAGE_PATH (a folder per entry, its name the package).
using PackagePaths = std::vector<std::pair<std::string, std::filesystem::path>>;

struct ReadOptions {
  GeometrySource from = GeometrySource::collision;
  PackagePaths packages;
};

/// A robot file and its links, in the file's order.
struct Robot {
  RobotFormat format = RobotFormat::urdf;
  std::filesystem::path file;
  std::string text;  ///< the file's bytes, unchanged
  std::vector<Link> links;
};

/// Reads a URDF (.urdf), SDF (.sdf, .world) or MJCF (.xml whose root is <mujoco>) file.
/// Throws InputError "FILE: ..." naming the element or attribute on malformed XML, unknown
/// formats, bad numbers and mesh paths that cannot be resolved.
Robot read_robot(const std::filesystem::path& file, const ReadOptions& options);

/// The format readers, given the file's text (read_robot picks one).
Robot read_urdf(const std::filesystem::path& file, std::string text, const ReadOptions& options);
Robot read_sdf(const std::filesystem::path& file, std::string text, const ReadOptions& options);
Robot read_mjcf(const std::filesystem::path& file, std::string text, const ReadOptions& options);

/// A mesh path of a robot file resolved to a file: relative to the robot file's folder (or to
/// `base`, e.g. MJCF's meshdir), `file://` URIs, and `package://NAME/REST` through `packages`.
/// Throws InputError "FILE: WHERE: ..." when it cannot be resolved.
std::filesystem::path resolve_mesh_path(const std::string& uri, const std::filesystem::path& base,
                                        const PackagePaths& packages, const std::string& where);

}  // namespace tumble::app::robot
