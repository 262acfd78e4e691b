// Tests of mesh import: every format the issue lists, node transforms, and the error messages.
//
// Each fixture is written at test time (mesh_fixtures.hpp) and run through the same pipeline as
// `tumble inspect`: analyze_mesh(import_mesh(file)). The oracle is the closed form of the solid
// (boxes, prisms over a polygon) mapped by the file's node transforms, so the test checks the
// reader, the node walk and the integration together against numbers derived independently.
//
// What assimp 5.2.5 does with each format, as measured when these tests were written:
// - STL, OBJ: no scene graph (an identity root, one child node per `solid`/`o`), unindexed
//   (a vertex per face corner), welded by tumble. ASCII STL with several `solid` blocks gives one
//   aiMesh per block. OBJ quads and n-gons, convex or not, are triangulated by assimp.
// - PLY, OFF: one indexed mesh on the root node; n-gon faces are triangulated.
// - glTF 2.0 (.gltf with a base64 data URI, and .glb): node TRS becomes aiNode::mTransformation
//   (T * R * S); no axis or unit conversion (glTF's metres and +Y up are kept as they are).
// - FBX (ASCII 7.4): Lcl Translation/Rotation (Euler XYZ, degrees, R = Rz Ry Rx)/Scaling
//   become one node's transformation under "RootNode"; GlobalSettings UnitScaleFactor and the
//   axis settings are only copied into the scene metadata: without aiProcess_GlobalScale (not
//   requested by import_mesh) the coordinates arrive unscaled, in file units, so an FBX in
//   centimetres needs --scale 0.01 like any other file. Rotations go through float sin/cos
//   (cos 90 degrees = -4.4e-8), hence the looser tolerance of the rotated FBX case.
// - Coordinates are stored as float32, so fixtures use values exact in float (integers,
//   halves, quarters) and are compared to 1e-12; non-exact rotations get 1e-6.
#include "engine/import/mesh_import.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "base/errors.hpp"
#include "engine/mass/mesh_analysis.hpp"
#include "engine/mesh_fixtures.hpp"
#include "support/input_error.hpp"

namespace tumble::engine {
namespace {

using mesh_fixtures::GltfNode;
using mesh_fixtures::Polyhedron;
using mesh_fixtures::SolidMoments;
using mesh_fixtures::TempDir;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using ::testing::StartsWith;
using tumble::testing::input_error_of;
namespace fixtures = mesh_fixtures;

constexpr double kDensity = 1000.0;    // analyze_mesh's default
constexpr double kFloatExact = 1e-12;  // float-exact coordinates and transforms
constexpr double kFloat = 1e-6;        // transforms that pass through float rounding

// The reference solid: a 2 x 3 x 4 box centred at (3, -1, 2.5), all corners exact in float.
const Eigen::Vector3d kLow(2.0, -2.5, 0.5);
const Eigen::Vector3d kHigh(4.0, 0.5, 4.5);

Polyhedron test_box() {
  return fixtures::box(kLow, kHigh);
}
SolidMoments test_box_moments() {
  return fixtures::box_moments(kLow, kHigh);
}

// A convex hexagon with exact coordinates (not regular: sqrt(3) is not a float).
const std::vector<Eigen::Vector2d> kHexagon = {{2.0, 0.0},  {1.0, 2.0},   {-1.0, 2.0},
                                               {-2.0, 0.0}, {-1.0, -2.0}, {1.0, -2.0}};

// An L outline starting at the vertex (3, 1) from which a fan would leave the polygon.
const std::vector<Eigen::Vector2d> kEll = {{3.0, 1.0}, {1.0, 1.0}, {1.0, 3.0},
                                           {0.0, 3.0}, {0.0, 0.0}, {3.0, 0.0}};

// A T outline: stem [-1, 1] x [-2, 2] under a bar [-3, 3] x [2, 3].
const std::vector<Eigen::Vector2d> kTee = {{-1.0, -2.0}, {1.0, -2.0}, {1.0, 2.0},  {3.0, 2.0},
                                           {3.0, 3.0},   {-3.0, 3.0}, {-3.0, 2.0}, {-1.0, 2.0}};

/// x -> linear x + translation of a glTF node (T * R * S).
struct Affine {
  Eigen::Matrix3d linear = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();

  Affine operator*(const Affine& inner) const {
    return {linear * inner.linear, linear * inner.translation + translation};
  }
};

Affine trs(const std::array<double, 3>& t, const std::array<double, 4>& q,
           const std::array<double, 3>& s) {
  Affine out;
  out.linear = fixtures::quaternion_matrix(q[0], q[1], q[2], q[3]) *
               Eigen::Vector3d(s[0], s[1], s[2]).asDiagonal();
  out.translation = Eigen::Vector3d(t[0], t[1], t[2]);
  return out;
}

SolidMoments transformed(const SolidMoments& moments, const Affine& affine) {
  return moments.transformed(affine.linear, affine.translation);
}

GltfNode gltf_node(std::optional<std::size_t> mesh, std::array<double, 3> t,
                   std::array<double, 4> q, std::array<double, 3> s,
                   std::vector<std::size_t> children = {}) {
  return {mesh, t, q, s, std::move(children)};
}

MeshReport analyze_file(const std::filesystem::path& file) {
  return analyze_mesh(import_mesh(file), {}, file.string());
}

/// Checks a report against the closed form: a closed, consistently outward body (nothing
/// flipped, no warnings) with the expected volume, mass, centre of mass and inertia.
void expect_body(const MeshReport& report, const SolidMoments& expected, double tolerance) {
  EXPECT_TRUE(report.watertight);
  EXPECT_FALSE(report.flipped) << "winding arrived inward";
  EXPECT_THAT(report.warnings, IsEmpty());
  EXPECT_EQ(report.boundary_edges, 0u);
  EXPECT_EQ(report.inconsistent_edges, 0u);
  EXPECT_EQ(report.cavities, 0u);
  EXPECT_NEAR(report.volume, expected.volume, tolerance * expected.volume);
  EXPECT_NEAR(report.mass_properties.mass, kDensity * expected.volume,
              tolerance * kDensity * expected.volume);
  // Centre of mass: relative to the body's size or distance from the origin, whichever is more.
  const Eigen::Vector3d com = expected.center_of_mass();
  const double length = std::max(com.norm(), std::cbrt(expected.volume));
  EXPECT_LE((report.mass_properties.center_of_mass - com).norm(), tolerance * length)
      << "got " << report.mass_properties.center_of_mass.transpose() << ", expected "
      << com.transpose();
  const Eigen::Matrix3d inertia = expected.inertia(kDensity);
  EXPECT_LE((report.mass_properties.inertia - inertia).norm(), tolerance * inertia.norm())
      << "got\n"
      << report.mass_properties.inertia << "\nexpected\n"
      << inertia;
}

// --- The oracle itself ---------------------------------------------------------------------

TEST(MeshImportOracle, PrismOverRectangleIsTheBoxAndBoxInertiaIsTextbook) {
  const SolidMoments from_prism = fixtures::prism_moments(
      {{kLow.x(), kLow.y()}, {kHigh.x(), kLow.y()}, {kHigh.x(), kHigh.y()}, {kLow.x(), kHigh.y()}},
      kLow.z(), kHigh.z());
  const SolidMoments box = test_box_moments();
  EXPECT_NEAR(from_prism.volume, 24.0, 1e-12);
  EXPECT_LE((from_prism.first - box.first).norm(), 1e-12);
  EXPECT_LE((from_prism.second - box.second).norm(), 1e-12);
  // m (b^2 + c^2) / 12 etc. with m = 24000 kg.
  EXPECT_LE((box.inertia(kDensity) -
             Eigen::Vector3d(50000.0, 40000.0, 26000.0).asDiagonal().toDenseMatrix())
                .norm(),
            1e-8);
  EXPECT_LE((box.center_of_mass() - Eigen::Vector3d(3.0, -1.0, 2.5)).norm(), 1e-15);
}

TEST(MeshImportOracle, RotatedInertiaIsRotatedTensor) {
  // For a rotation R: I -> R I R^T and c -> R c + t.
  const Eigen::Matrix3d unit =
      Eigen::Quaterniond(0.9, 0.1, 0.2, 0.3).normalized().toRotationMatrix();
  const Eigen::Vector3d t(1.0, -2.0, 3.0);
  const SolidMoments moved = test_box_moments().transformed(unit, t);
  const SolidMoments box = test_box_moments();
  EXPECT_NEAR(moved.volume, box.volume, 1e-12);
  EXPECT_LE((moved.center_of_mass() - (unit * box.center_of_mass() + t)).norm(), 1e-12);
  EXPECT_LE((moved.inertia(kDensity) - unit * box.inertia(kDensity) * unit.transpose()).norm(),
            1e-8);
}

// --- Formats -------------------------------------------------------------------------------

TEST(MeshImport, BinaryStl) {
  TempDir dir;
  const auto file = dir / "box.stl";
  fixtures::write_stl_binary(file, fixtures::fan_triangulated(test_box()));
  const MeshReport report = analyze_file(file);
  EXPECT_EQ(report.input_triangles, 12u);
  EXPECT_EQ(report.vertices, 8u);  // 36 corners welded
  expect_body(report, test_box_moments(), kFloatExact);
}

TEST(MeshImport, AsciiStl) {
  TempDir dir;
  const auto file = dir / "box.stl";
  fixtures::write_stl_ascii(file, {fixtures::fan_triangulated(test_box())});
  expect_body(analyze_file(file), test_box_moments(), kFloatExact);
}

TEST(MeshImport, AsciiStlWithTwoSolidsIsOneBody) {
  TempDir dir;
  const auto file = dir / "two.stl";
  const Eigen::Vector3d low(10.0, 0.0, -1.0), high(11.0, 1.5, 1.0);
  fixtures::write_stl_ascii(file, {fixtures::fan_triangulated(test_box()),
                                   fixtures::fan_triangulated(fixtures::box(low, high))});
  const MeshReport report = analyze_file(file);
  EXPECT_EQ(report.parts, 2u);
  expect_body(report, test_box_moments() + fixtures::box_moments(low, high), kFloatExact);
}

TEST(MeshImport, ObjWithQuads) {
  TempDir dir;
  const auto file = dir / "box.obj";
  fixtures::write_obj(file, {test_box()});
  const MeshReport report = analyze_file(file);
  EXPECT_EQ(report.input_triangles, 12u);
  expect_body(report, test_box_moments(), kFloatExact);
}

TEST(MeshImport, ObjWithHexagonCaps) {
  TempDir dir;
  const auto file = dir / "hexagonal_prism.obj";
  fixtures::write_obj(file, {fixtures::prism(kHexagon, -1.5, 2.25)});
  const MeshReport report = analyze_file(file);
  EXPECT_EQ(report.input_triangles, 2u * 4u + 6u * 2u);
  expect_body(report, fixtures::prism_moments(kHexagon, -1.5, 2.25), kFloatExact);
}

TEST(MeshImport, ObjWithNonConvexCaps) {
  // Oracles from boxes, independent of the polygon formula: L = two boxes, T = two boxes.
  TempDir dir;
  const auto ell_file = dir / "ell.obj";
  fixtures::write_obj(ell_file, {fixtures::prism(kEll, -1.0, 1.5)});
  const SolidMoments ell = fixtures::box_moments({0.0, 0.0, -1.0}, {3.0, 1.0, 1.5}) +
                           fixtures::box_moments({0.0, 1.0, -1.0}, {1.0, 3.0, 1.5});
  const MeshReport ell_report = analyze_file(ell_file);
  EXPECT_EQ(ell_report.input_triangles, 2u * 4u + 6u * 2u);
  expect_body(ell_report, ell, kFloatExact);

  const auto tee_file = dir / "tee.obj";
  fixtures::write_obj(tee_file, {fixtures::prism(kTee, 0.5, 4.0)});
  const SolidMoments tee = fixtures::box_moments({-1.0, -2.0, 0.5}, {1.0, 2.0, 4.0}) +
                           fixtures::box_moments({-3.0, 2.0, 0.5}, {3.0, 3.0, 4.0});
  const MeshReport tee_report = analyze_file(tee_file);
  EXPECT_EQ(tee_report.input_triangles, 2u * 6u + 8u * 2u);
  expect_body(tee_report, tee, kFloatExact);
}

TEST(MeshImport, ObjWithTwoObjectsIsOneBody) {
  TempDir dir;
  const auto file = dir / "two.obj";
  fixtures::write_obj(file, {test_box(), fixtures::prism(kHexagon, 10.0, 11.0)});
  const MeshReport report = analyze_file(file);
  EXPECT_EQ(report.parts, 2u);
  expect_body(report, test_box_moments() + fixtures::prism_moments(kHexagon, 10.0, 11.0),
              kFloatExact);
}

TEST(MeshImport, ObjIgnoresPointsAndLinesBesideTriangles) {
  TempDir dir;
  const auto file = dir / "box_and_lines.obj";
  fixtures::write_obj(file, {test_box()});
  // Append a polyline and points over the box's vertices (OBJ indices are 1-based).
  std::string text;
  {
    std::ifstream in(file);
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  fixtures::write_file(file, text + "v 100 100 100\nl 1 2 3 9\np 4 5 9\n");
  expect_body(analyze_file(file), test_box_moments(), kFloatExact);
}

TEST(MeshImport, PlyAscii) {
  TempDir dir;
  const auto file = dir / "box.ply";
  fixtures::write_ply(file, test_box(), /*binary=*/false);
  expect_body(analyze_file(file), test_box_moments(), kFloatExact);
}

TEST(MeshImport, PlyBinaryLittleEndianWithNonConvexCaps) {
  TempDir dir;
  const auto file = dir / "tee.ply";
  fixtures::write_ply(file, fixtures::prism(kTee, 0.5, 4.0), /*binary=*/true);
  expect_body(analyze_file(file), fixtures::prism_moments(kTee, 0.5, 4.0), kFloatExact);
}

TEST(MeshImport, PlyBinaryLittleEndianBox) {
  TempDir dir;
  const auto file = dir / "box.ply";
  fixtures::write_ply(file, test_box(), /*binary=*/true);
  expect_body(analyze_file(file), test_box_moments(), kFloatExact);
}

TEST(MeshImport, Off) {
  TempDir dir;
  const auto file = dir / "box.off";
  fixtures::write_off(file, test_box());
  expect_body(analyze_file(file), test_box_moments(), kFloatExact);
}

TEST(MeshImport, OffWithHexagonCaps) {
  TempDir dir;
  const auto file = dir / "hexagonal_prism.off";
  fixtures::write_off(file, fixtures::prism(kHexagon, -1.5, 2.25));
  expect_body(analyze_file(file), fixtures::prism_moments(kHexagon, -1.5, 2.25), kFloatExact);
}

// --- glTF 2.0 node transforms ----------------------------------------------------------------

// Translation, a rotation of 120 degrees about (1, 1, 1) (x -> y -> z -> x; the quaternion
// (1/2, 1/2, 1/2, 1/2) and its matrix are exact in float) and a non-uniform scale.
constexpr std::array<double, 3> kTranslation{10.0, -20.0, 5.25};
constexpr std::array<double, 4> kCycleAxes{0.5, 0.5, 0.5, 0.5};
constexpr std::array<double, 3> kScale{2.0, 0.5, 1.5};

TEST(MeshImport, GltfNodeTranslationRotationScale) {
  for (const bool binary : {false, true}) {
    SCOPED_TRACE(binary ? "glb" : "gltf");
    TempDir dir;
    const auto file = dir / (binary ? "box.glb" : "box.gltf");
    fixtures::write_gltf(file, {{test_box()}}, {gltf_node(0, kTranslation, kCycleAxes, kScale)},
                         {0}, binary);
    const Affine node = trs(kTranslation, kCycleAxes, kScale);
    // The rotation really permutes the axes: the 2 x 3 x 4 box scaled to 4 x 1.5 x 6 becomes
    // 6 x 4 x 1.5, and its inertia is R I R^T of the scaled box.
    const MeshReport report = analyze_file(file);
    EXPECT_LE((report.bounds_max - report.bounds_min - Eigen::Vector3d(6.0, 4.0, 1.5)).norm(),
              1e-12);
    expect_body(report, transformed(test_box_moments(), node), kFloatExact);
    const SolidMoments scaled =
        transformed(test_box_moments(), trs({0, 0, 0}, {0, 0, 0, 1}, kScale));
    const Eigen::Matrix3d rotation = fixtures::quaternion_matrix(0.5, 0.5, 0.5, 0.5);
    EXPECT_LE((report.mass_properties.inertia -
               rotation * scaled.inertia(kDensity) * rotation.transpose())
                  .norm(),
              1e-12 * scaled.inertia(kDensity).norm());
  }
}

TEST(MeshImport, GltfGeneralRotationWithinFloatAccuracy) {
  TempDir dir;
  const auto file = dir / "box.gltf";
  const Eigen::Quaterniond q = Eigen::Quaterniond(0.9, 0.1, -0.2, 0.3).normalized();
  const std::array<double, 4> rotation{q.x(), q.y(), q.z(), q.w()};
  fixtures::write_gltf(file, {{test_box()}}, {gltf_node(0, kTranslation, rotation, {1, 1, 1})}, {0},
                       false);
  expect_body(analyze_file(file),
              transformed(test_box_moments(), trs(kTranslation, rotation, {1, 1, 1})), kFloat);
}

TEST(MeshImport, GltfNestedNodeTransformsCompose) {
  // root (scale 2) -> parent (translate, cycle axes) -> child (translate, 180 degrees about x,
  // scale) -> mesh: the mesh sees root * parent * child.
  TempDir dir;
  const auto file = dir / "nested.gltf";
  const std::array<double, 3> no_translation{0, 0, 0}, unit{1, 1, 1};
  const std::array<double, 4> no_rotation{0, 0, 0, 1}, half_turn_x{1, 0, 0, 0};
  const std::vector<GltfNode> nodes = {
      gltf_node(std::nullopt, no_translation, no_rotation, {2, 2, 2}, {1}),
      gltf_node(std::nullopt, {1, 2, 3}, kCycleAxes, unit, {2}),
      gltf_node(0, {-4, 0.25, 8}, half_turn_x, {1, 2, 0.5}),
  };
  fixtures::write_gltf(file, {{test_box()}}, nodes, {0}, false);
  const Affine world = trs(no_translation, no_rotation, {2, 2, 2}) *
                       trs({1, 2, 3}, kCycleAxes, unit) *
                       trs({-4, 0.25, 8}, half_turn_x, {1, 2, 0.5});
  expect_body(analyze_file(file), transformed(test_box_moments(), world), kFloatExact);
}

TEST(MeshImport, GltfMirroringScaleKeepsBodyOutward) {
  // scale (-1, 1, 1) turns the outward winding inward; import must reverse it: positive volume,
  // nothing flipped by analyze_mesh, no warning, centre of mass mirrored to (-3, -1, 2.5).
  TempDir dir;
  const auto file = dir / "mirrored.gltf";
  fixtures::write_gltf(file, {{test_box()}}, {gltf_node(0, {0, 0, 0}, {0, 0, 0, 1}, {-1, 1, 1})},
                       {0}, false);
  const MeshReport report = analyze_file(file);
  expect_body(report, transformed(test_box_moments(), trs({0, 0, 0}, {0, 0, 0, 1}, {-1, 1, 1})),
              kFloatExact);
  EXPECT_LE((report.mass_properties.center_of_mass - Eigen::Vector3d(-3.0, -1.0, 2.5)).norm(),
            1e-12);
  EXPECT_GT(report.volume, 0.0);
}

TEST(MeshImport, GltfMirrorsComposeAcrossTheHierarchy) {
  // Two mirrors (parent x, child y) make a proper rotation: no reversal needed. Beside it, an
  // instance with one mirror. Both must come out outward: a part left inward would be flipped
  // with a warning by analyze_mesh, which expect_body rejects.
  TempDir dir;
  const auto file = dir / "mirrors.gltf";
  const std::array<double, 4> none{0, 0, 0, 1};
  const std::vector<GltfNode> nodes = {
      gltf_node(std::nullopt, {0, 0, 0}, none, {-1, 1, 1}, {1}),
      gltf_node(0, {0, 0, 0}, none, {1, -1, 1}),
      gltf_node(0, {0, 0, 20}, none, {1, 1, -0.5}),
  };
  fixtures::write_gltf(file, {{test_box()}}, nodes, {0, 2}, false);
  const SolidMoments expected =
      transformed(test_box_moments(), trs({0, 0, 0}, none, {-1, -1, 1})) +
      transformed(test_box_moments(), trs({0, 0, 20}, none, {1, 1, -0.5}));
  const MeshReport report = analyze_file(file);
  EXPECT_EQ(report.parts, 2u);
  expect_body(report, expected, kFloatExact);
}

TEST(MeshImport, GltfMeshesPrimitivesAndInstancesCombineIntoOneBody) {
  // Mesh 0: the box. Mesh 1: two primitives (a hexagonal prism and a T prism), which assimp
  // splits into two aiMeshes. Mesh 0 is instanced twice, once mirrored.
  for (const bool binary : {false, true}) {
    SCOPED_TRACE(binary ? "glb" : "gltf");
    TempDir dir;
    const auto file = dir / (binary ? "scene.glb" : "scene.gltf");
    const std::array<double, 4> none{0, 0, 0, 1};
    const std::vector<GltfNode> nodes = {
        gltf_node(0, {0, 0, 0}, none, {1, 1, 1}),
        gltf_node(1, {20, 0, 0}, kCycleAxes, {1, 1, 1}),
        gltf_node(0, {-20, 0, 0}, none, {-1, 1, 1}),
    };
    fixtures::write_gltf(
        file,
        {{test_box()}, {fixtures::prism(kHexagon, 0.0, 1.0), fixtures::prism(kTee, 5.0, 6.0)}},
        nodes, {0, 1, 2}, binary);
    const Affine second = trs({20, 0, 0}, kCycleAxes, {1, 1, 1});
    const SolidMoments expected =
        test_box_moments() + transformed(fixtures::prism_moments(kHexagon, 0.0, 1.0), second) +
        transformed(fixtures::prism_moments(kTee, 5.0, 6.0), second) +
        transformed(test_box_moments(), trs({-20, 0, 0}, none, {-1, 1, 1}));
    const MeshReport report = analyze_file(file);
    EXPECT_EQ(report.parts, 4u);
    expect_body(report, expected, kFloatExact);
  }
}

// --- FBX -------------------------------------------------------------------------------------

Eigen::Matrix3d euler_xyz_degrees(const std::array<double, 3>& degrees) {
  // FBX's default rotation order eEulerXYZ applies x first: R = Rz Ry Rx.
  const auto about = [&](int axis) {
    return Eigen::AngleAxisd(degrees[axis] * std::numbers::pi / 180.0, Eigen::Vector3d::Unit(axis))
        .toRotationMatrix();
  };
  return about(2) * about(1) * about(0);
}

Affine fbx_transform(const fixtures::FbxModel& model) {
  Affine out;
  out.linear = euler_xyz_degrees(model.rotation_degrees) *
               Eigen::Vector3d(model.scaling[0], model.scaling[1], model.scaling[2]).asDiagonal();
  out.translation =
      Eigen::Vector3d(model.translation[0], model.translation[1], model.translation[2]);
  return out;
}

TEST(MeshImport, FbxModelTranslationAndScalingIgnoringUnitScaleFactor) {
  // assimp 5.2.5 records UnitScaleFactor in the scene metadata but leaves the coordinates in
  // file units (no aiProcess_GlobalScale): the same file in centimetres (1, FBX's default) and
  // declared in metres (100) gives the same body.
  const fixtures::FbxModel model{test_box(), {10.0, -20.0, 5.25}, {0.0, 0.0, 0.0}, {2.0, 0.5, 1.5}};
  for (const double unit_scale_factor : {1.0, 100.0}) {
    SCOPED_TRACE(unit_scale_factor);
    TempDir dir;
    const auto file = dir / "box.fbx";
    fixtures::write_fbx_ascii(file, {model}, unit_scale_factor);
    expect_body(analyze_file(file), transformed(test_box_moments(), fbx_transform(model)),
                kFloatExact);
  }
}

TEST(MeshImport, FbxModelRotationIsEulerXyz) {
  TempDir dir;
  const auto file = dir / "box.fbx";
  const fixtures::FbxModel model{test_box(), {1.0, 2.0, 3.0}, {30.0, -45.0, 60.0}, {1.0, 2.0, 0.5}};
  fixtures::write_fbx_ascii(file, {model}, 1.0);
  expect_body(analyze_file(file), transformed(test_box_moments(), fbx_transform(model)), kFloat);
}

TEST(MeshImport, FbxTwoModelsOneMirroredCombineIntoOneBody) {
  TempDir dir;
  const auto file = dir / "two.fbx";
  const fixtures::FbxModel plain{test_box(), {0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}};
  const fixtures::FbxModel mirrored{
      fixtures::prism(kTee, 0.0, 2.0), {0.0, 0.0, 30.0}, {0.0, 0.0, 0.0}, {1.0, -1.0, 1.0}};
  fixtures::write_fbx_ascii(file, {plain, mirrored}, 1.0);
  const MeshReport report = analyze_file(file);
  EXPECT_EQ(report.parts, 2u);
  expect_body(report,
              test_box_moments() +
                  transformed(fixtures::prism_moments(kTee, 0.0, 2.0), fbx_transform(mirrored)),
              kFloatExact);
}

// --- Errors ----------------------------------------------------------------------------------

TEST(MeshImportErrors, NoSuchFile) {
  TempDir dir;
  const auto file = dir / "missing.stl";
  const std::string message = input_error_of([&] { import_mesh(file); });
  EXPECT_THAT(message, StartsWith(file.string() + ": "));
  EXPECT_THAT(message, HasSubstr("no such file"));
}

TEST(MeshImportErrors, Directory) {
  TempDir dir;
  const auto folder = dir / "meshes.obj";
  std::filesystem::create_directory(folder);
  const std::string message = input_error_of([&] { import_mesh(folder); });
  EXPECT_THAT(message, StartsWith(folder.string() + ": "));
  EXPECT_THAT(message, HasSubstr("is a directory"));
}

TEST(MeshImportErrors, EmptyFile) {
  TempDir dir;
  for (const char* name : {"empty.stl", "empty.obj", "empty.gltf"}) {
    const auto file = dir / name;
    fixtures::write_file(file, "");
    const std::string message = input_error_of([&] { import_mesh(file); });
    EXPECT_THAT(message, StartsWith(file.string() + ": "));
    EXPECT_THAT(message, HasSubstr("is empty"));
  }
}

/// Bytes with no ASCII in them, so no text format's signature can match by chance.
std::string garbage() {
  std::string bytes;
  for (int i = 0; i < 1000; ++i) bytes.push_back(static_cast<char>(0x80 + (i * 37) % 128));
  return bytes;
}

TEST(MeshImportErrors, UnknownFormat) {
  // assimp: "No suitable reader found for the file format of file ...".
  TempDir dir;
  for (const char* name : {"noise.xyz", "noise"}) {
    const auto file = dir / name;
    fixtures::write_file(file, garbage());
    const std::string message = input_error_of([&] { import_mesh(file); });
    EXPECT_THAT(message, StartsWith(file.string() + ": "));
    EXPECT_THAT(message, HasSubstr("unknown or unsupported mesh format"));
  }
}

TEST(MeshImportErrors, GarbageWithAKnownExtension) {
  // The extension picks assimp's STL reader, which gives up with "Failed to determine STL
  // storage representation for noise.stl."; import_mesh passes the reason on.
  TempDir dir;
  const auto file = dir / "noise.stl";
  fixtures::write_file(file, garbage());
  const std::string message = input_error_of([&] { import_mesh(file); });
  EXPECT_THAT(message, StartsWith(file.string() + ": "));
  EXPECT_THAT(message, HasSubstr("cannot be read as a mesh"));
  EXPECT_THAT(message, HasSubstr("STL"));
}

TEST(MeshImportErrors, TruncatedGltf) {
  // assimp 5.2.5's glTF readers parse the JSON (or GLB header) to decide whether they can read
  // the file at all, so a damaged .gltf or .glb reaches import_mesh as "No suitable reader"
  // and is reported as an unknown format (naming the file, but not the damage).
  TempDir dir;
  const auto gltf = dir / "truncated.gltf";
  const auto glb = dir / "truncated.glb";
  fixtures::write_gltf(gltf, {{test_box()}}, {gltf_node(0, {0, 0, 0}, {0, 0, 0, 1}, {1, 1, 1})},
                       {0}, false);
  fixtures::write_gltf(glb, {{test_box()}}, {gltf_node(0, {0, 0, 0}, {0, 0, 0, 1}, {1, 1, 1})}, {0},
                       true);
  for (const auto& file : {gltf, glb}) {
    SCOPED_TRACE(file.filename().string());
    std::filesystem::resize_file(file, std::filesystem::file_size(file) / 2);
    const std::string message = input_error_of([&] { import_mesh(file); });
    EXPECT_THAT(message, StartsWith(file.string() + ": "));
    EXPECT_THAT(message, HasSubstr("unknown or unsupported mesh format"));
  }
}

TEST(MeshImportErrors, GltfWithMissingExternalBuffer) {
  TempDir dir;
  const auto file = dir / "external.gltf";
  fixtures::write_file(
      file, R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
            R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
            R"("buffers":[{"byteLength":36,"uri":"missing.bin"}],)"
            R"("bufferViews":[{"buffer":0,"byteLength":36}],)"
            R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"}]})");
  const std::string message = input_error_of([&] { import_mesh(file); });
  EXPECT_THAT(message, StartsWith(file.string() + ": "));
  EXPECT_THAT(message, HasSubstr("cannot be read as a mesh"));
  EXPECT_THAT(message, HasSubstr("missing.bin"));
}

TEST(MeshImportErrors, GarbageObjHoldsNoTriangles) {
  // assimp's OBJ parser skips lines it does not know, so binary noise is an empty scene.
  TempDir dir;
  const auto file = dir / "noise.obj";
  fixtures::write_file(file, garbage());
  const std::string message = input_error_of([&] { import_mesh(file); });
  EXPECT_THAT(message, StartsWith(file.string() + ": "));
  EXPECT_THAT(message, HasSubstr("contains no triangles"));
}

TEST(MeshImportErrors, OnlyPointsAndLines) {
  // Asking assimp to remove points and lines (AI_CONFIG_PP_SBP_REMOVE) would make it fail such a
  // file with "No meshes remaining"; import_mesh skips them itself and says what is missing.
  TempDir dir;
  const auto file = dir / "wire.obj";
  fixtures::write_file(file, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nl 1 2 3 4 1\np 1 2 3 4\n");
  const std::string message = input_error_of([&] { import_mesh(file); });
  EXPECT_THAT(message, StartsWith(file.string() + ": "));
  EXPECT_THAT(message, HasSubstr("contains no triangles"));
}

TEST(MeshImportErrors, NonFiniteCoordinates) {
  // assimp's text parsers (fast_atof) keep "nan" and "inf" as such, and binary formats carry
  // any bit pattern: all must be rejected at import, naming the file.
  TempDir dir;
  const std::string tetrahedron_faces = "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  fixtures::write_file(dir / "nan.obj",
                       "v nan 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n" + tetrahedron_faces);
  fixtures::write_file(dir / "inf.obj",
                       "v 0 0 0\nv 1 0 0\nv 0 -inf 0\nv 0 0 1\n" + tetrahedron_faces);
  fixtures::write_file(dir / "inf.ply",
                       "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\n"
                       "property float y\nproperty float z\nelement face 4\n"
                       "property list uchar int vertex_indices\nend_header\n"
                       "0 0 0\n1 0 0\n0 1 0\n0 0 inf\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
  Polyhedron box = fixtures::fan_triangulated(test_box());
  box.vertices[5].y() = std::nan("");
  fixtures::write_stl_binary(dir / "nan.stl", box);
  Polyhedron glb_box = test_box();
  glb_box.vertices[2].z() = INFINITY;
  fixtures::write_gltf(dir / "inf.glb", {{glb_box}},
                       {gltf_node(0, {0, 0, 0}, {0, 0, 0, 1}, {1, 1, 1})}, {0}, true);
  for (const char* name : {"nan.obj", "inf.obj", "inf.ply", "nan.stl", "inf.glb"}) {
    SCOPED_TRACE(name);
    const auto file = dir / name;
    const std::string message = input_error_of([&] { import_mesh(file); });
    EXPECT_THAT(message, StartsWith(file.string() + ": "));
    EXPECT_THAT(message, HasSubstr("non-finite coordinate"));
  }
}

TEST(MeshImportErrors, OpenMeshSuggestsShell) {
  TempDir dir;
  const auto file = dir / "open_box.obj";
  Polyhedron open = test_box();
  open.faces.pop_back();
  fixtures::write_obj(file, {open});
  const std::string message = input_error_of([&] { analyze_file(file); });
  EXPECT_THAT(message, StartsWith(file.string() + ": "));
  EXPECT_THAT(message, HasSubstr("open"));
  EXPECT_THAT(message, HasSubstr("--shell"));
  // The same file is a valid thin shell.
  MassOptions shell;
  shell.shell_thickness = 0.001;
  const MeshReport report = analyze_mesh(import_mesh(file), shell, file.string());
  EXPECT_NEAR(report.area, 2.0 * (2.0 * 3.0 + 2.0 * 4.0 + 3.0 * 4.0) - 3.0 * 4.0, 1e-12);
}

}  // namespace
}  // namespace tumble::engine
