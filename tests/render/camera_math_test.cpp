#include "render/camera_math.hpp"

#include <gtest/gtest.h>

#include "render_support.hpp"

namespace tumble::render {
namespace {

TEST(CameraMath, TargetProjectsToTheImageCentre) {
  Camera camera;
  const Eigen::Vector3f pixel = project_to_pixels(camera, 96, 64, camera.target);
  EXPECT_NEAR(pixel.x(), 48.0f, 1e-4f);
  EXPECT_NEAR(pixel.y(), 32.0f, 1e-4f);
  EXPECT_NEAR(pixel.z(), (camera.eye - camera.target).norm(), 1e-4f);  // w = view depth
}

TEST(CameraMath, AgreesWithAnIndependentPinholeModel) {
  Camera camera;
  camera.eye = {2.0f, -3.0f, 1.5f};
  camera.target = {0.1f, 0.2f, -0.3f};
  camera.vertical_fov_deg = 55.0f;
  for (const Eigen::Vector3f& p :
       {Eigen::Vector3f(0.5f, 0.5f, 0.5f), Eigen::Vector3f(-1.0f, 0.3f, 0.0f),
        Eigen::Vector3f(0.0f, 0.0f, 1.0f)}) {
    const Eigen::Vector3f ours = project_to_pixels(camera, 320, 200, p);
    const Eigen::Vector2f theirs = testing::pinhole_project(camera, 320, 200, p);
    EXPECT_NEAR(ours.x(), theirs.x(), 1e-3f);
    EXPECT_NEAR(ours.y(), theirs.y(), 1e-3f);
  }
}

TEST(CameraMath, DepthRangeMapsNearAndFarPlanes) {
  Camera camera;
  camera.eye = Eigen::Vector3f::Zero();
  camera.target = -Eigen::Vector3f::UnitZ();
  camera.up = Eigen::Vector3f::UnitY();
  const Eigen::Matrix4f vp = projection_matrix(camera, 1.5f) * view_matrix(camera);
  const Eigen::Vector4f near_clip = vp * Eigen::Vector4f(0, 0, -camera.near_plane, 1);
  const Eigen::Vector4f far_clip = vp * Eigen::Vector4f(0, 0, -camera.far_plane, 1);
  EXPECT_NEAR(near_clip.z() / near_clip.w(), -1.0f, 1e-5f);
  EXPECT_NEAR(far_clip.z() / far_clip.w(), 1.0f, 1e-4f);
}

}  // namespace
}  // namespace tumble::render
