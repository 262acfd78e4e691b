// The shipped demo meshes (assets/meshes) are valid rigid bodies with the symmetry their
// demos rely on, and they are exactly what assets/tools/make_meshes.cpp writes.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/geometry/triangle_mesh.hpp"
#include "engine/mass/mesh_analysis.hpp"

namespace tumble::engine {
namespace {

using ::testing::HasSubstr;
using ::testing::IsEmpty;

const std::filesystem::path kMeshDirectory = TUMBLE_SOURCE_DIR "/assets/meshes";
const std::filesystem::path kGenerator = TUMBLE_BINARY_DIR "/assets/make_meshes";

std::string read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path.string() + ": cannot open");
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A deliberately tiny OBJ reader (v and f lines; "f a/b/c" forms reduced to the position index;
// polygons fanned), independent of the assimp importer.
TriangleMesh read_obj(const std::filesystem::path& path) {
  std::istringstream in(read_bytes(path));
  TriangleMesh mesh;
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    std::istringstream fields(line);
    std::string tag;
    fields >> tag;
    const std::string where = path.filename().string() + ":" + std::to_string(line_number);
    if (tag == "v") {
      Eigen::Vector3d p;
      if (!(fields >> p.x() >> p.y() >> p.z())) throw std::runtime_error(where + ": bad vertex");
      mesh.positions.push_back(p);
    } else if (tag == "f") {
      std::vector<std::uint32_t> corners;
      std::string corner;
      while (fields >> corner) {
        const long index = std::stol(corner.substr(0, corner.find('/')));
        if (index < 1 || static_cast<std::size_t>(index) > mesh.positions.size()) {
          throw std::runtime_error(where + ": face index out of range");
        }
        corners.push_back(static_cast<std::uint32_t>(index - 1));
      }
      if (corners.size() < 3) throw std::runtime_error(where + ": face with < 3 corners");
      for (std::size_t k = 1; k + 1 < corners.size(); ++k) {
        mesh.triangles.push_back({corners[0], corners[k], corners[k + 1]});
      }
    }
  }
  return mesh;
}

enum class Symmetry {
  kNone,     // three distinct principal moments
  kOblate,   // axis z, I1 = I2 < I3 (disc-like)
  kProlate,  // axis z, I1 < I2 = I3 (cigar-like)
};

struct Asset {
  const char* file;
  std::size_t parts;
  Symmetry symmetry;
  Eigen::Vector3d extent;  // bounding-box size, m
};

void PrintTo(const Asset& asset, std::ostream* out) {
  *out << asset.file;
}

class ShippedMesh : public ::testing::TestWithParam<Asset> {};

TEST_P(ShippedMesh, IsAValidRigidBodyWithTheIntendedShape) {
  const Asset& asset = GetParam();
  const TriangleMesh mesh = read_obj(kMeshDirectory / asset.file);
  const MeshReport report = analyze_mesh(mesh, MassOptions{}, asset.file);

  // Clean topology: nothing welded, skipped, flipped or warned about.
  EXPECT_TRUE(report.watertight);
  EXPECT_THAT(report.warnings, IsEmpty());
  EXPECT_EQ(report.parts, asset.parts);
  EXPECT_EQ(report.cavities, 0u);
  EXPECT_FALSE(report.flipped);
  EXPECT_EQ(report.welded_vertices, 0u);
  EXPECT_EQ(report.degenerate_triangles, 0u);
  EXPECT_LE(report.triangles, 20000u);
  EXPECT_GE(report.triangles, 1000u);

  // Realistic size.
  const Eigen::Vector3d extent = report.bounds_max - report.bounds_min;
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_NEAR(extent[axis], asset.extent[axis], 0.02 * asset.extent[axis]) << "axis " << axis;
  }

  // Principal moments: distinct, or a symmetric pair about the z axis.
  const Eigen::Vector3d& moments = report.principal.moments;
  const auto gap = [&](int low, int high) {
    return (moments[high] - moments[low]) / moments[high];
  };
  switch (asset.symmetry) {
    case Symmetry::kNone:
      EXPECT_GT(gap(0, 1), 0.05) << moments.transpose();
      EXPECT_GT(gap(1, 2), 0.05) << moments.transpose();
      break;
    case Symmetry::kOblate:
      EXPECT_LT(gap(0, 1), 1e-3) << moments.transpose();
      EXPECT_GT(gap(1, 2), 0.05) << moments.transpose();
      EXPECT_NEAR(std::abs(report.principal.axes.col(2).z()), 1.0, 1e-9);
      break;
    case Symmetry::kProlate:
      EXPECT_GT(gap(0, 1), 0.05) << moments.transpose();
      EXPECT_LT(gap(1, 2), 1e-3) << moments.transpose();
      EXPECT_NEAR(std::abs(report.principal.axes.col(0).z()), 1.0, 1e-9);
      break;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Assets, ShippedMesh,
    ::testing::Values(Asset{"t_handle.obj", 1, Symmetry::kNone, {0.080, 0.059, 0.010}},
                      Asset{"tennis_racket.obj", 3, Symmetry::kNone, {0.265, 0.680, 0.022}},
                      Asset{"spinning_top.obj", 1, Symmetry::kOblate, {0.060, 0.060, 0.062}},
                      Asset{"coin.obj", 1, Symmetry::kOblate, {0.024, 0.024, 0.002}},
                      Asset{"rugby_ball.obj", 1, Symmetry::kProlate, {0.190, 0.190, 0.280}},
                      Asset{"asteroid.obj", 1, Symmetry::kNone, {545.0, 310.0, 224.0}}),
    [](const ::testing::TestParamInfo<Asset>& param) {
      const std::string file = param.param.file;
      return file.substr(0, file.find('.'));
    });

TEST(ShippedMeshes, SayWhereTheyComeFrom) {
  for (const char* file : {"t_handle.obj", "tennis_racket.obj", "spinning_top.obj", "coin.obj",
                           "rugby_ball.obj", "asteroid.obj"}) {
    const std::string text = read_bytes(kMeshDirectory / file);
    EXPECT_THAT(text.substr(0, 400), HasSubstr("Generated by assets/tools/make_meshes.cpp"))
        << file;
    EXPECT_THAT(text.substr(0, 400), HasSubstr("Units: metres")) << file;
  }
}

TEST(ShippedMeshes, AreExactlyWhatTheGeneratorWrites) {
  const std::filesystem::path output =
      std::filesystem::temp_directory_path() / ("tumble_make_meshes_" + std::to_string(::getpid()));
  std::filesystem::remove_all(output);
  const std::string command = kGenerator.string() + " " + output.string() + " > /dev/null";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;

  std::size_t compared = 0;
  for (const auto& entry : std::filesystem::directory_iterator(output)) {
    const std::filesystem::path shipped = kMeshDirectory / entry.path().filename();
    ASSERT_TRUE(std::filesystem::exists(shipped)) << shipped << " is not shipped";
    EXPECT_TRUE(read_bytes(entry.path()) == read_bytes(shipped))
        << shipped << " differs from a fresh run of make_meshes; regenerate with: "
        << "make_meshes assets/meshes";
    ++compared;
  }
  EXPECT_EQ(compared, 6u);
  std::filesystem::remove_all(output);
}

}  // namespace
}  // namespace tumble::engine
