// `tumble view --allow-overlap`: a mesh opened on its own whose parts overlap is their exact
// union, as `tumble inspect` takes it, or with the option each part counted whole
// (RunChoice::allow_overlap, --overlap sum).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>

#include "app/viewer/viewer_session.hpp"
#include "engine/geometry/primitive_meshes.hpp"
#include "render/renderer.hpp"
#include "support/run_command.hpp"
#include "support/stl_writer.hpp"

namespace tumble::app::viewer {
namespace {

using ::testing::HasSubstr;

/// Two unit cubes whose corners overlap by half an edge along x.
std::filesystem::path crossing_cubes() {
  engine::TriangleMesh mesh = engine::box_mesh(Eigen::Vector3d::Ones());
  engine::TriangleMesh second = engine::box_mesh(Eigen::Vector3d::Ones());
  for (Eigen::Vector3d& p : second.positions) p += Eigen::Vector3d(0.5, 0.25, 0.125);
  engine::append_mesh(mesh, second);
  const auto file = tumble::testing::fresh_directory("viewer_overlap") / "crossing.stl";
  tumble::testing::write_binary_stl(file, mesh);
  return file;
}

TEST(ViewerOverlap, AnOverlappingMeshIsTheirUnionOrWithAllowOverlapTheirSum) {
  render::RendererOptions options;
  options.width = 160;
  options.height = 120;
  render::Renderer renderer(options);
  const auto file = crossing_cubes();

  Session united(renderer);
  const auto union_error = united.open(file);
  EXPECT_FALSE(union_error) << *union_error;
  EXPECT_EQ(united.run_count(), 1u);

  Session allowed(renderer);
  RunChoice choice;
  choice.allow_overlap = true;
  const auto no_error = allowed.open(file, choice);
  EXPECT_FALSE(no_error) << *no_error;
  EXPECT_EQ(allowed.run_count(), 1u);
  EXPECT_EQ(mesh_scene(file, true).bodies.at(0).overlap, engine::OverlapMode::kSum);
  EXPECT_EQ(mesh_scene(file).bodies.at(0).overlap, engine::OverlapMode::kUnion);
}

}  // namespace
}  // namespace tumble::app::viewer
