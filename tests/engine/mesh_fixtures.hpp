#pragma once
/// @file Known solids, their closed-form moments, and writers that put them into mesh files
/// (STL, OBJ, PLY, OFF, glTF 2.0, FBX) at test time. No binary fixtures are committed: every
/// file a test reads is written here, into a temporary directory.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "engine/geometry/primitive_meshes.hpp"
#include "engine/geometry/triangle_mesh.hpp"

namespace tumble::mesh_fixtures {

/// A closed polyhedron as polygons wound counter-clockwise seen from outside.
struct Polyhedron {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::vector<std::uint32_t>> faces;
};

/// The axis-aligned box [low, high] with its six faces as quads.
Polyhedron box(const Eigen::Vector3d& low, const Eigen::Vector3d& high);

/// The prism swept by a simple polygon `outline` (counter-clockwise in the xy plane, convex or
/// not) from z = z_low to z = z_high; the two caps are single n-gons, the sides quads.
Polyhedron prism(const std::vector<Eigen::Vector2d>& outline, double z_low, double z_high);

/// The same polyhedron with every face fanned into triangles (convex faces only).
Polyhedron fan_triangulated(const Polyhedron& polyhedron);

/// Moments of a uniform solid of unit density about the world origin: additive over disjoint
/// solids, so a body made of several pieces is the sum of theirs.
struct SolidMoments {
  double volume = 0.0;                               ///< integral of 1
  Eigen::Vector3d first = Eigen::Vector3d::Zero();   ///< integral of x
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();  ///< integral of x x^T

  SolidMoments operator+(const SolidMoments& other) const;
  /// The moments of the image of the solid under x -> linear x + translation (any invertible
  /// linear map, mirrors included: the volume element scales by |det linear|).
  SolidMoments transformed(const Eigen::Matrix3d& linear, const Eigen::Vector3d& translation) const;
  Eigen::Vector3d center_of_mass() const { return first / volume; }
  /// Inertia tensor about the centre of mass of matter of `density`.
  Eigen::Matrix3d inertia(double density) const;
};

/// Closed form for the box [low, high].
SolidMoments box_moments(const Eigen::Vector3d& low, const Eigen::Vector3d& high);

/// Closed form for a prism over a simple polygon (Green's theorem on the outline, e.g.
/// Steger, "On the calculation of arbitrary moments of polygons", 1996).
SolidMoments prism_moments(const std::vector<Eigen::Vector2d>& outline, double z_low,
                           double z_high);

/// Rotation matrix of the unit quaternion (x, y, z, w), as glTF stores it.
Eigen::Matrix3d quaternion_matrix(double x, double y, double z, double w);

/// A temporary directory removed (with its contents) when the object goes away.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

/// Writes `bytes` verbatim.
void write_file(const std::filesystem::path& file, const std::string& bytes);

/// The mesh_import fuzz input `name` (tests/fuzz/corpus/mesh_import/) as a file in `dir`: its
/// first byte chose the extension, the rest is the file.
std::filesystem::path fuzz_input_as_file(const std::string& name, const TempDir& dir);

/// The bytes of a binary STL (80-byte header, little-endian float32); faces must be triangles.
/// The default header does not start with "solid", which some readers take for ASCII.
std::string binary_stl_bytes(const Polyhedron& mesh,
                             const std::string& header = "binary STL written by tumble's tests");
/// Binary STL with the default header.
void write_stl_binary(const std::filesystem::path& file, const Polyhedron& mesh);
/// ASCII STL with one `solid` block per element; faces must be triangles.
void write_stl_ascii(const std::filesystem::path& file, const std::vector<Polyhedron>& solids);
/// Wavefront OBJ with one `o` object per element, faces as written (quads, n-gons).
void write_obj(const std::filesystem::path& file, const std::vector<Polyhedron>& objects);
/// PLY 1.0, ASCII or binary little-endian (float32 coordinates, int32 indices).
void write_ply(const std::filesystem::path& file, const Polyhedron& mesh, bool binary);
/// Object File Format (OFF), faces as written.
void write_off(const std::filesystem::path& file, const Polyhedron& mesh);

/// A glTF node: TRS (any of them optional) and optionally a mesh and children.
struct GltfNode {
  std::optional<std::size_t> mesh;
  std::optional<std::array<double, 3>> translation;
  std::optional<std::array<double, 4>> rotation;  ///< quaternion x, y, z, w
  std::optional<std::array<double, 3>> scale;
  std::vector<std::size_t> children;
};

/// A glTF 2.0 file: `meshes[i]` is a list of primitives (each triangulated by fanning), the
/// scene's roots are `roots`. `binary` writes a .glb container, else .gltf JSON with the buffer
/// embedded as a base64 data URI.
void write_gltf(const std::filesystem::path& file,
                const std::vector<std::vector<Polyhedron>>& meshes,
                const std::vector<GltfNode>& nodes, const std::vector<std::size_t>& roots,
                bool binary);

/// An FBX model: one geometry with local translation, Euler XYZ rotation (degrees) and scaling.
struct FbxModel {
  Polyhedron geometry;
  std::array<double, 3> translation{0.0, 0.0, 0.0};
  std::array<double, 3> rotation_degrees{0.0, 0.0, 0.0};
  std::array<double, 3> scaling{1.0, 1.0, 1.0};
};

/// ASCII FBX 7.4 with the given models under the root and GlobalSettings UnitScaleFactor
/// `unit_scale_factor` (centimetres per file unit; FBX's default is 1).
void write_fbx_ascii(const std::filesystem::path& file, const std::vector<FbxModel>& models,
                     double unit_scale_factor);

/// Standard base64 (RFC 4648) with padding.
std::string base64(const std::string& bytes);

/// `mesh` with every triangle's winding reversed (inside out).
inline engine::TriangleMesh reversed(engine::TriangleMesh mesh) {
  for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
  return mesh;
}

/// `a` and `b` as one mesh (b's vertices and triangles appended, not welded).
inline engine::TriangleMesh joined(engine::TriangleMesh a, const engine::TriangleMesh& b) {
  engine::append_mesh(a, b);
  return a;
}

}  // namespace tumble::mesh_fixtures
