// Tests of what import_mesh does with files that are broken, hostile or not files at all
// (issue 12): scenes assimp returns half-built, headers that declare more than the file holds,
// paths that are FIFOs or symbolic-link loops, and faces the importer drops on the way.
//
// Every case is a small file written here; each message is checked word for word where it
// matters, and each case crashed, hung, ran out of memory or was accepted before the fix.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <string>

#include "engine/import/mesh_import.hpp"
#include "engine/mass/mesh_analysis.hpp"
#include "engine/mesh_fixtures.hpp"
#include "support/input_error.hpp"

namespace tumble::engine {
namespace {

using mesh_fixtures::TempDir;
using ::testing::HasSubstr;
using ::testing::StartsWith;
using tumble::testing::input_error_of;
namespace fixtures = mesh_fixtures;

/// The unit right tetrahedron (volume 1/6) in OBJ, faces wound outward.
const std::string kTetrahedronObj =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

/// Its vertices and faces as the data of an OFF or ASCII PLY file.
const std::string kTetrahedronVertices = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
const std::string kTetrahedronFaces = "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";

std::string ply_header(std::uint64_t vertices, std::uint64_t faces, const char* format) {
  return std::string("ply\nformat ") + format + " 1.0\ncomment element vertex 99\nelement vertex " +
         std::to_string(vertices) +
         "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
         std::to_string(faces) + "\nproperty list uchar int vertex_indices\nend_header\n";
}

// --- 1. what assimp returns is checked before it is used

TEST(MeshImportScene, NullChildNodeOfARawFileIsRefusedNotFollowed) {
  // assimp 5.2's RAW reader leaves the second group's node null (assimp-testmodels'
  // RAW/WithColor.raw crashed tumble with SIGSEGV).
  TempDir dir;
  const auto file = dir / "two_groups.raw";
  fixtures::write_file(file, "first\n0 0 0 1 0 0 0 1 0\n\n\nsecond\n0 0 1 1 0 1 0 1 1\n");
  const std::string message = input_error_of([&] { import_mesh(file); });
  EXPECT_EQ(message, file.string() +
                         ": assimp returned a broken scene: child 2 of node '<RawRoot>' is "
                         "missing, so some of the file's meshes would be lost");
}

TEST(MeshImportScene, VertexIndexPastTheMeshIsRefused) {
  // assimp's PLY reader passes index 9 of a 4-vertex mesh through; it was read out of bounds.
  TempDir dir;
  const auto file = dir / "bad_index.ply";
  fixtures::write_file(file, ply_header(4, 4, "ascii") + kTetrahedronVertices +
                                 "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 9\n");
  const std::string message = input_error_of([&] { import_mesh(file); });
  EXPECT_EQ(message, file.string() +
                         ": face 4 of mesh 0 refers to vertex index 9, but the mesh has 4 "
                         "vertices (indices from 0)");
}

TEST(MeshImportScene, ObjFacesOfOneOrTwoCornersAreSkippedNotReadPastTheirEnd) {
  // assimp 5.2 flags a mesh of `f 1 2` faces as triangles only; 6 KB of them crashed tumble.
  TempDir dir;
  const auto lines = dir / "lines.obj";
  std::string text = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  for (int i = 0; i < 1200; ++i) text += i % 2 == 0 ? "f 1 2\n" : "f 3\n";
  fixtures::write_file(lines, text);
  ASSERT_GT(std::filesystem::file_size(lines), 5000u);
  EXPECT_EQ(input_error_of([&] { import_mesh(lines); }),
            lines.string() + ": contains no triangles");

  // Beside real triangles they are skipped, counted and reported.
  const auto mixed = dir / "mixed.obj";
  fixtures::write_file(mixed, kTetrahedronObj + "f 1 2\nf 3 4\nf 2\n");
  ImportStats stats;
  const MeshReport report = analyze_mesh(import_mesh(mixed, &stats), {}, mixed.string());
  EXPECT_EQ(report.triangles, 4u);
  EXPECT_NEAR(report.volume, 1.0 / 6.0, 1e-15);
  EXPECT_EQ(stats.skipped_faces, 3u);
  ASSERT_EQ(stats.warnings.size(), 1u);
  EXPECT_EQ(stats.warnings[0],
            "skipped 3 faces of fewer than three corners (points and lines, which enclose "
            "nothing)");
}

// --- 2. declared counts against the file's size, before assimp trusts them

/// Seconds `action` takes.
template <typename Action>
double seconds_of(Action&& action) {
  const auto start = std::chrono::steady_clock::now();
  action();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

TEST(MeshImportCounts, OffDeclaringMoreVerticesThanItsBytesIsRefusedAtOnce) {
  // assimp-testmodels' invalid/OutOfMemory.off: assimp took 15 GiB and aborted.
  TempDir dir;
  const auto file = dir / "huge.off";
  fixtures::write_file(file, "OFF\n353535235358 6 0\n" + kTetrahedronVertices);
  std::string message;
  const double took = seconds_of([&] { message = input_error_of([&] { import_mesh(file); }); });
  EXPECT_LT(took, 0.5);
  EXPECT_EQ(message, file.string() +
                         ": the OFF header declares 353535235358 vertices and 6 faces: "
                         "at least 2121211412160 bytes after the header, but the file has 25 "
                         "(truncated, or the counts are wrong)");
}

TEST(MeshImportCounts, TruncatedOffIsRefusedByItsLineCount) {
  TempDir dir;
  const auto file = dir / "short.off";
  fixtures::write_file(file, "OFF\n# a comment\n4 4 0\n" + kTetrahedronVertices + "3 0 2 1\n\n");
  EXPECT_EQ(input_error_of([&] { import_mesh(file); }),
            file.string() +
                ": the OFF header declares 4 vertices and 4 faces: at least 8 lines "
                "after the header, but the file has 5 (truncated, or the counts are wrong)");
}

TEST(MeshImportCounts, TruncatedAsciiPlyIsRefusedByItsLineCount) {
  // assimp made up the two missing faces; a comment naming an element does not count.
  TempDir dir;
  const auto file = dir / "short.ply";
  fixtures::write_file(file, ply_header(4, 4, "ascii") + kTetrahedronVertices + "3 0 2 1\n");
  EXPECT_EQ(input_error_of([&] { import_mesh(file); }),
            file.string() +
                ": the PLY header declares 4 'vertex', 4 'face' elements: at least 8 "
                "lines after the header, but the file has 5 (truncated, or the counts are "
                "wrong)");
}

TEST(MeshImportCounts, BinaryPlyDeclaringMoreThanItsBytesIsRefusedAtOnce) {
  TempDir dir;
  const auto file = dir / "huge.ply";
  fixtures::write_file(
      file, ply_header(2'000'000'000, 1, "binary_little_endian") + std::string(48, '\0'));
  std::string message;
  const double took = seconds_of([&] { message = input_error_of([&] { import_mesh(file); }); });
  EXPECT_LT(took, 0.5);
  EXPECT_EQ(message, file.string() +
                         ": the PLY header declares 2000000000 'vertex', 1 'face' elements: at "
                         "least 24000000001 bytes after the header, but the file has 48 "
                         "(truncated, or the counts are wrong)");
}

TEST(MeshImportCounts, TruncatedBinaryStlClaimingABillionTrianglesGetsTumblesWording) {
  // With either reader: assimp would say "Failed to determine STL storage representation", or
  // read a header starting with "solid" as an empty ASCII file.
  TempDir dir;
  for (const char* header : {"binary", "solid but binary"}) {
    std::string bytes = std::string(header) + std::string(80 - std::string(header).size(), ' ');
    bytes += std::string("\x00\xca\x9a\x3b", 4);  // 10^9, little-endian
    bytes += std::string(600, 'A');
    const auto file = dir / "truncated.stl";
    fixtures::write_file(file, bytes);
    for (const StlReader reader : {StlReader::tumble, StlReader::assimp}) {
      EXPECT_EQ(input_error_of([&] { import_mesh(file, nullptr, reader); }),
                file.string() +
                    ": cannot be read as a mesh: a binary STL declaring 1000000000 triangles "
                    "takes 50000000084 bytes, but the file has 684 (truncated)")
          << header;
    }
  }
}

TEST(MeshImportCounts, AsciiStlWithAUtf8NameIsNotTakenForATruncatedBinaryOne) {
  // Bytes above 127 after "solid" (a name in UTF-8), and a size that is no binary STL's.
  TempDir dir;
  const auto file = dir / "wuerfel.stl";
  std::string text = "solid W\xc3\xbcrfel\n";
  const char* const faces[4][3] = {{"0 0 0", "0 1 0", "1 0 0"},
                                   {"0 0 0", "1 0 0", "0 0 1"},
                                   {"0 0 0", "0 0 1", "0 1 0"},
                                   {"1 0 0", "0 1 0", "0 0 1"}};
  for (const auto& face : faces) {
    text += "facet normal 0 0 0\nouter loop\n";
    for (const char* corner : face) text += std::string("vertex ") + corner + "\n";
    text += "endloop\nendfacet\n";
  }
  fixtures::write_file(file, text + "endsolid W\xc3\xbcrfel\n");
  for (const StlReader reader : {StlReader::tumble, StlReader::assimp}) {
    const MeshReport report = analyze_mesh(import_mesh(file, nullptr, reader), {}, file.string());
    EXPECT_EQ(report.triangles, 4u);
    EXPECT_NEAR(report.volume, 1.0 / 6.0, 1e-15);
  }
}

// --- 3. only regular files are opened

TEST(MeshImportPaths, FifoIsRefusedWithoutOpeningIt) {
  // Opening a FIFO blocks until a writer comes: this test hung before the fix.
  TempDir dir;
  const auto fifo = dir / "pipe.stl";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(input_error_of([&] { import_mesh(fifo); }),
            fifo.string() + ": is a FIFO (named pipe), not a regular file");
  // The same through a symbolic link, which is followed.
  const auto link = dir / "link.stl";
  std::filesystem::create_symlink(fifo, link);
  EXPECT_EQ(input_error_of([&] { import_mesh(link); }),
            link.string() + ": is a FIFO (named pipe), not a regular file");
}

TEST(MeshImportPaths, SymbolicLinkLoopIsReportedAsOne) {
  TempDir dir;
  std::filesystem::create_symlink(dir / "b.stl", dir / "a.stl");
  std::filesystem::create_symlink(dir / "a.stl", dir / "b.stl");
  EXPECT_EQ(input_error_of([&] { import_mesh(dir / "a.stl"); }),
            (dir / "a.stl").string() + ": is a loop of symbolic links");
}

TEST(MeshImportPaths, DanglingSymbolicLinkNamesItsTarget) {
  TempDir dir;
  std::filesystem::create_symlink(dir / "gone.stl", dir / "link.stl");
  EXPECT_EQ(input_error_of([&] { import_mesh(dir / "link.stl"); }),
            (dir / "link.stl").string() + ": is a symbolic link to a missing file (" +
                (dir / "gone.stl").string() + ")");
}

TEST(MeshImportPaths, CharacterDeviceIsRefused) {
  EXPECT_EQ(input_error_of([&] { import_mesh("/dev/zero"); }),
            "/dev/zero: is a character device, not a regular file");
}

// --- 4. faces the importer dropped

TEST(MeshImportDroppedFaces, OffFaceAssimpSkipsIsRefusedByName) {
  // assimp 5.2 skips a face line it cannot parse and reads the other four.
  TempDir dir;
  const auto file = dir / "malformed.off";
  fixtures::write_file(file, "OFF\n4 5 0\n" + kTetrahedronVertices + kTetrahedronFaces + "x\n");
  EXPECT_EQ(input_error_of([&] { import_mesh(file); }),
            file.string() +
                ": the OFF header declares 5 faces, but assimp read only 4: the rest were "
                "dropped (malformed or truncated), so the mass properties would be those of "
                "part of the file");
}

TEST(MeshImportDroppedFaces, ObjFaceLineAssimpSkipsIsRefusedByName) {
  // `f /1 /2 /3` (no vertex before the slash) vanishes in assimp 5.2 without an error.
  TempDir dir;
  const auto file = dir / "malformed.obj";
  fixtures::write_file(file, kTetrahedronObj + "f /1 /2 /3\nf \n");
  EXPECT_EQ(input_error_of([&] { import_mesh(file); }),
            file.string() +
                ": has 5 face lines ('f'), but assimp read only 4: the rest were dropped "
                "(malformed or truncated), so the mass properties would be those of part of "
                "the file");
}

TEST(MeshImportDroppedFaces, CompleteFilesPassTheCrossCheck) {
  TempDir dir;
  const auto off = dir / "tetrahedron.off";
  fixtures::write_file(off, "OFF\n4 4 0\n" + kTetrahedronVertices + kTetrahedronFaces);
  const auto ply = dir / "tetrahedron.ply";
  fixtures::write_file(ply, ply_header(4, 4, "ascii") + kTetrahedronVertices + kTetrahedronFaces);
  const auto obj = dir / "tetrahedron.obj";
  fixtures::write_file(obj, kTetrahedronObj);
  for (const auto& file : {off, ply, obj}) {
    const MeshReport report = analyze_mesh(import_mesh(file), {}, file.string());
    EXPECT_EQ(report.triangles, 4u) << file;
    EXPECT_NEAR(report.volume, 1.0 / 6.0, 1e-15) << file;
  }
}

// --- files that hold no solid

TEST(MeshImportPlaceholders, AMotionCaptureSkeletonIsRefusedNotMeasured) {
  // assimp draws the bones of a BVH or CSM skeleton as a placeholder mesh; CSM's placeholder
  // was measured as a body (assimp-testmodels' CSM/ThomasFechten.csm, "volume" 7.8e8).
  TempDir dir;
  const auto file = dir / "walk.bvh";
  fixtures::write_file(file,
                       "HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0 0\n  CHANNELS 3 Xposition Yposition "
                       "Zposition\n  JOINT Chest\n  {\n    OFFSET 0 5 0\n    CHANNELS 3 Zrotation "
                       "Xrotation Yrotation\n    End Site\n    {\n      OFFSET 0 5 0\n    }\n  }\n"
                       "}\nMOTION\nFrames: 2\nFrame Time: 0.04\n0 0 0 0 0 0\n0 1 0 0 10 0\n");
  EXPECT_EQ(input_error_of([&] { import_mesh(file); }),
            file.string() +
                ": holds no solid, only an animated skeleton (motion capture): the mesh assimp "
                "makes to show its bones is a placeholder, not a body");
}

}  // namespace
}  // namespace tumble::engine
