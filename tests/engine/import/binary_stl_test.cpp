// Tests of tumble's own binary STL reader. The oracle is assimp: on every file, the mesh the
// default import makes must be the very mesh import_mesh makes when assimp reads the file
// (same positions bit for bit, same triangles, same welding counts, same error text), and the
// reader must claim exactly the files it is meant to (binary STL by size, named *.stl).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>

#include "base/errors.hpp"
#include "engine/geometry/primitive_meshes.hpp"
#include "engine/import/mesh_import.hpp"
#include "engine/mass/mesh_analysis.hpp"
#include "engine/mesh_fixtures.hpp"
#include "support/input_error.hpp"

namespace tumble::engine {
namespace {

namespace fixtures = mesh_fixtures;
using fixtures::Polyhedron;
using fixtures::TempDir;
using ::testing::HasSubstr;
using ::testing::StartsWith;

Polyhedron polyhedron_of(const TriangleMesh& mesh) {
  Polyhedron out;
  out.vertices = mesh.positions;
  for (const auto& t : mesh.triangles) out.faces.push_back({t[0], t[1], t[2]});
  return out;
}

/// A torus of 600 x 300 segments (360,000 triangles, 1.08 M corners: enough for the welding
/// and the widening to run on two threads) with its triangles shuffled and a third of them
/// starting at another corner (the winding kept), so that corners repeat far apart.
Polyhedron shuffled_torus() {
  Polyhedron torus = polyhedron_of(torus_mesh(1.0, 0.3, 600, 300));
  std::mt19937 random(7);
  std::shuffle(torus.faces.begin(), torus.faces.end(), random);
  for (std::size_t f = 0; f < torus.faces.size(); f += 3) {
    std::rotate(torus.faces[f].begin(), torus.faces[f].begin() + 1, torus.faces[f].end());
  }
  return torus;
}

struct Imported {
  TriangleMesh mesh;
  ImportStats stats;
};

Imported import_with(const std::filesystem::path& file, StlReader reader) {
  Imported out;
  out.mesh = import_mesh(file, &out.stats, reader);
  return out;
}

/// The two readers' meshes are identical, and tumble's own reader read the file.
void expect_same_as_assimp(const std::filesystem::path& file) {
  const Imported own = import_with(file, StlReader::tumble);
  const Imported assimp = import_with(file, StlReader::assimp);
  EXPECT_TRUE(own.stats.own_stl_reader);
  EXPECT_FALSE(assimp.stats.own_stl_reader);
  EXPECT_EQ(own.stats.welded_vertices, assimp.stats.welded_vertices);
  EXPECT_EQ(own.stats.distinct_positions, assimp.stats.distinct_positions);
  ASSERT_EQ(own.mesh.positions.size(), assimp.mesh.positions.size());
  ASSERT_EQ(own.mesh.triangles.size(), assimp.mesh.triangles.size());
  std::size_t position_mismatches = 0, triangle_mismatches = 0;
  for (std::size_t i = 0; i < own.mesh.positions.size(); ++i) {
    // Bit for bit: -0 and +0 are welded together, so compare what was kept, sign included.
    for (int axis = 0; axis < 3; ++axis) {
      const double a = own.mesh.positions[i][axis], b = assimp.mesh.positions[i][axis];
      if (a != b || std::signbit(a) != std::signbit(b)) ++position_mismatches;
    }
  }
  for (std::size_t t = 0; t < own.mesh.triangles.size(); ++t) {
    if (own.mesh.triangles[t] != assimp.mesh.triangles[t]) ++triangle_mismatches;
  }
  EXPECT_EQ(position_mismatches, 0u);
  EXPECT_EQ(triangle_mismatches, 0u);
}

/// The InputError text of importing `file` with `reader`.
std::string import_error(const std::filesystem::path& file, StlReader reader) {
  return tumble::testing::input_error_of([&] { import_mesh(file, nullptr, reader); },
                                         file.string());
}

TEST(BinaryStl, BoxIsAssimpsMeshAndTheClosedForm) {
  TempDir dir;
  const auto file = dir / "box.stl";
  const Eigen::Vector3d low(2.0, -2.5, 0.5), high(4.0, 0.5, 4.5);
  fixtures::write_stl_binary(file, fixtures::fan_triangulated(fixtures::box(low, high)));
  expect_same_as_assimp(file);
  // 36 corners weld into 8 vertices; the body is the 2 x 3 x 4 box.
  ImportStats stats;
  const MeshReport report =
      analyze_mesh(import_mesh(file, &stats), {}, file.string(), stats.distinct_positions);
  EXPECT_EQ(stats.welded_vertices, 28u);
  EXPECT_EQ(report.vertices, 8u);
  EXPECT_NEAR(report.volume, 24.0, 1e-12);
  EXPECT_LE((report.mass_properties.center_of_mass - Eigen::Vector3d(3.0, -1.0, 2.5)).norm(),
            1e-12);
}

TEST(BinaryStl, LargeShuffledSoupIsAssimpsMesh) {
  TempDir dir;
  const auto file = dir / "torus.stl";
  const Polyhedron torus = shuffled_torus();
  fixtures::write_stl_binary(file, torus);
  expect_same_as_assimp(file);
  // Every corner of a closed torus is shared: 600 x 300 vertices survive.
  ImportStats stats;
  const TriangleMesh mesh = import_mesh(file, &stats);
  EXPECT_EQ(mesh.positions.size(), 180'000u);
  EXPECT_EQ(stats.welded_vertices, 3 * torus.faces.size() - 180'000u);
}

TEST(BinaryStl, SignedZerosAndDegenerateTrianglesAsAssimp) {
  // A tetrahedron written with -0 at some corners where others have +0, plus a triangle that
  // repeats a corner: welding and what follows must treat them as assimp's path does.
  Polyhedron tetrahedron;
  tetrahedron.vertices = {{0.0, 0.0, 0.0}, {1.0, 0.0, 0.0},   {0.0, 1.0, 0.0},
                          {0.0, 0.0, 1.0}, {-0.0, -0.0, 0.0}, {1.0, -0.0, -0.0}};
  tetrahedron.faces = {{0, 2, 1}, {4, 1, 3}, {0, 3, 2}, {5, 2, 3}, {1, 1, 3}};
  TempDir dir;
  const auto file = dir / "zeros.stl";
  fixtures::write_stl_binary(file, tetrahedron);
  expect_same_as_assimp(file);
  const MeshReport report = analyze_mesh(import_mesh(file), {}, file.string());
  EXPECT_EQ(report.vertices, 4u);
  EXPECT_EQ(report.degenerate_triangles, 1u);
  EXPECT_NEAR(report.volume, 1.0 / 6.0, 1e-15);
}

TEST(BinaryStl, HeaderThatLooksLikeAsciiIsStillBinary) {
  // Some exporters start the binary header with "solid"; both readers go by the size.
  TempDir dir;
  const auto file = dir / "solid_header.stl";
  fixtures::write_file(file, fixtures::binary_stl_bytes(
                                 fixtures::fan_triangulated(fixtures::box({0, 0, 0}, {1, 2, 3})),
                                 "solid exported by a CAD program"));
  expect_same_as_assimp(file);
  EXPECT_NEAR(analyze_mesh(import_mesh(file), {}, file.string()).volume, 6.0, 1e-12);
}

TEST(BinaryStl, UpperCaseExtensionIsClaimed) {
  TempDir dir;
  const auto file = dir / "BOX.STL";
  fixtures::write_stl_binary(file, fixtures::fan_triangulated(fixtures::box({0, 0, 0}, {1, 1, 1})));
  expect_same_as_assimp(file);
}

TEST(BinaryStl, OtherFilesAreLeftToAssimp) {
  TempDir dir;
  const Polyhedron box = fixtures::fan_triangulated(fixtures::box({0, 0, 0}, {1, 1, 2}));
  // ASCII STL, and a binary STL under another name (which assimp does not take for STL).
  const auto ascii = dir / "ascii.stl";
  fixtures::write_stl_ascii(ascii, {box});
  ImportStats stats;
  const TriangleMesh mesh = import_mesh(ascii, &stats);
  EXPECT_FALSE(stats.own_stl_reader);
  EXPECT_NEAR(analyze_mesh(mesh, {}, ascii.string()).volume, 2.0, 1e-12);
  const auto renamed = dir / "box.bin";
  fixtures::write_stl_binary(renamed, box);
  EXPECT_EQ(import_error(renamed, StlReader::tumble), import_error(renamed, StlReader::assimp));
}

TEST(BinaryStl, WrongSizeIsRejectedAsByAssimp) {
  // One byte too many: not the size of a binary STL and not ASCII. assimp 5.2 refuses such a
  // file ("Failed to determine STL storage representation"); so does the default import.
  TempDir dir;
  const auto file = dir / "trailing.stl";
  fixtures::write_file(file, fixtures::binary_stl_bytes(
                                 fixtures::fan_triangulated(fixtures::box({0, 0, 0}, {1, 1, 2}))) +
                                 std::string(1, '\0'));
  const std::string message = import_error(file, StlReader::tumble);
  EXPECT_THAT(message, StartsWith(file.string() + ": cannot be read as a mesh"));
  EXPECT_EQ(message, import_error(file, StlReader::assimp));
}

TEST(BinaryStl, EmptyBinaryStlHasNoTriangles) {
  // 84 bytes declaring zero triangles is a well-formed binary STL with nothing in it.
  TempDir dir;
  const auto file = dir / "none.stl";
  fixtures::write_file(file, fixtures::binary_stl_bytes(Polyhedron{}));
  const std::string message = import_error(file, StlReader::tumble);
  EXPECT_THAT(message, StartsWith(file.string() + ": "));
  EXPECT_THAT(message, HasSubstr("contains no triangles"));
}

TEST(BinaryStl, TruncatedFileIsAnErrorNamingTheFile) {
  // The count promises two triangles, the file holds one and a half: not a binary STL by size,
  // and assimp rejects it.
  TempDir dir;
  const auto file = dir / "cut.stl";
  Polyhedron two;
  two.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  two.faces = {{0, 2, 1}, {0, 1, 3}};
  std::string bytes = fixtures::binary_stl_bytes(two);
  bytes.resize(bytes.size() - 25);
  fixtures::write_file(file, bytes);
  const std::string message = import_error(file, StlReader::tumble);
  EXPECT_THAT(message, StartsWith(file.string() + ": "));
  EXPECT_THAT(message, HasSubstr("cannot be read as a mesh"));
  EXPECT_EQ(message, import_error(file, StlReader::assimp));
}

TEST(BinaryStl, NonFiniteCoordinateIsTheSameErrorAsAssimps) {
  TempDir dir;
  for (const double bad : {std::nan(""), double{INFINITY}, -double{INFINITY}}) {
    Polyhedron box = fixtures::fan_triangulated(fixtures::box({0, 0, 0}, {1, 1, 1}));
    box.vertices[3].z() = bad;
    const auto file = dir / "bad.stl";
    fixtures::write_stl_binary(file, box);
    const std::string message = import_error(file, StlReader::tumble);
    EXPECT_THAT(message, StartsWith(file.string() + ": vertex "));
    EXPECT_THAT(message, HasSubstr("non-finite coordinate"));
    EXPECT_EQ(message, import_error(file, StlReader::assimp));
  }
}

}  // namespace
}  // namespace tumble::engine
