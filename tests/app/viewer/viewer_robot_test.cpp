// The viewer's robot mode without a window: opening a robot file (the scene closed, its meshes
// released), the picture drawn, a click picking a link, and back to a scene.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>

#include "app/viewer/viewer.hpp"
#include "render/camera_math.hpp"
#include "render/renderer.hpp"
#include "support/command_test.hpp"
#include "support/scene_builder.hpp"
#include "support/two_link_robot.hpp"

namespace tumble::app::viewer {
namespace {

using ::testing::HasSubstr;

constexpr int kRobotViewWidth = 320;
constexpr int kRobotViewHeight = 240;

class ViewerRobot : public testing::CommandTest {
 protected:
  static void SetUpTestSuite() {
    render::RendererOptions options;
    options.width = kRobotViewWidth;
    options.height = kRobotViewHeight;
    renderer_ = std::make_unique<render::Renderer>(options);
  }
  static void TearDownTestSuite() { renderer_.reset(); }
  void SetUp() override {
    CommandTest::SetUp();
    robot_ = dir_ / "two_link.urdf";
    std::ofstream(robot_) << testing::kTwoLinkUrdf;
    viewer_ = std::make_unique<Viewer>(*renderer_, dir_);
  }
  void TearDown() override {
    viewer_.reset();
    CommandTest::TearDown();
  }
  /// A left click (press and release) at pixel (x, y) of the view.
  void click(float x, float y) {
    viewer_->handle(MouseButtonEvent{0, true, x, y}, false, false);
    viewer_->handle(MouseButtonEvent{0, false, x, y}, false, false);
  }

  static std::unique_ptr<render::Renderer> renderer_;
  std::unique_ptr<Viewer> viewer_;
  std::filesystem::path robot_;
};
std::unique_ptr<render::Renderer> ViewerRobot::renderer_;

TEST_F(ViewerRobot, OpensARobotAndAClickSelectsALink) {
  const std::string scene =
      write_scene(testing::SceneBuilder().body(testing::BodyBuilder("b")).json());
  ASSERT_TRUE(viewer_->open(scene));
  const std::size_t scene_meshes = renderer_->mesh_count();

  ASSERT_TRUE(viewer_->open(robot_));
  ASSERT_NE(viewer_->robot(), nullptr);
  EXPECT_TRUE(viewer_->session().empty());
  EXPECT_EQ(viewer_->notices().back().text,
            "opened " + robot_.string() + ": 2 links, 1 differing from their computed inertials");
  // Two links' geometry and two stated boxes (translucent), two wire boxes of 6 lines each,
  // the legend panel; the scene's meshes were released first.
  const render::DrawList list = viewer_->frame();
  EXPECT_EQ(list.meshes.size(), 4u);
  for (const render::MeshInstance& mesh : list.meshes) EXPECT_LT(mesh.colour.a, 1.0f);
  EXPECT_EQ(list.polylines.size(), 12u);
  EXPECT_EQ(list.panels.size(), 1u);
  EXPECT_LE(renderer_->mesh_count(), scene_meshes + 4u);

  // A click on the arm selects it (its geometry turns the selection's colour); a drag does
  // not pick; a click on the sky clears the selection.
  const Eigen::Vector3f arm = render::project_to_pixels(
      list.camera, kRobotViewWidth, kRobotViewHeight, testing::kTwoLinkArmCenter.cast<float>());
  click(arm.x(), arm.y());
  ASSERT_EQ(viewer_->selected_link, std::optional<std::size_t>(1));
  const render::DrawList selected = viewer_->frame();
  EXPECT_EQ(selected.meshes[2].colour.r, kSelectedLinkColour.r);
  viewer_->handle(MouseButtonEvent{0, true, 2.0f, 2.0f}, false, false);
  viewer_->handle(MouseButtonEvent{0, false, arm.x() - 40.0f, arm.y()}, false, false);
  EXPECT_EQ(viewer_->selected_link, std::optional<std::size_t>(1));
  click(1.0f, 1.0f);
  EXPECT_EQ(viewer_->selected_link, std::nullopt);

  // The picture draws: the frame renders.
  const tumble::Image image = renderer_->render(viewer_->frame());
  EXPECT_EQ(image.width, kRobotViewWidth);

  // A robot that cannot be read keeps the one open; a scene replaces it.
  std::ofstream(dir_ / "broken.urdf") << "<robot name='x'><link";
  EXPECT_FALSE(viewer_->open(dir_ / "broken.urdf"));
  EXPECT_TRUE(viewer_->notices().back().error);
  EXPECT_THAT(viewer_->notices().back().text, HasSubstr("broken.urdf"));
  EXPECT_NE(viewer_->robot(), nullptr);
  ASSERT_TRUE(viewer_->open(scene));
  EXPECT_EQ(viewer_->robot(), nullptr);
  EXPECT_FALSE(viewer_->session().empty());
  EXPECT_EQ(renderer_->mesh_count(), scene_meshes);
}

}  // namespace
}  // namespace tumble::app::viewer
