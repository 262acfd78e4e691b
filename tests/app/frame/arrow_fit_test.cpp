// Arrows kept inside the frame: under an explicit camera too close for them, every arrow's tip
// is shrunk into the image, along its own direction, and the overlay states the factor.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "app/frame/frame_builder.hpp"
#include "frame_scene_setup.hpp"
#include "render/camera_math.hpp"

namespace tumble::app {
namespace {

constexpr int kArrowFitWidth = 80;
constexpr int kArrowFitHeight = 60;

/// A free brick (inertia only, so its box has sides ~1 m) with long arrows, seen side-on from +x, 4
/// m away, through a 20 degree field (0.7 m half-height).
constexpr const char* kCloseScene = R"({
  "duration": 1, "dt": 0.01,
  "bodies": [{"name": "brick", "inertia": {"principal": [0.4, 0.9, 1.1]}, "mass": 2,
              "angular_velocity": [0.5, 3.0, 0.2]}],
  "render": {"camera": {"target": [0, 0, 0], "distance": 4.0, "fov": 20, "azimuth": 0, "elevation": 0},
             "show": {"overlay": true}}
})";

TEST(ArrowFit, TipsOutsideTheFrameAreShrunkIntoItAlongTheirDirection) {
  const testing::FrameSceneSetup setup(kCloseScene, kArrowFitWidth, kArrowFitHeight);
  const engine::Simulation simulation = setup.simulation();
  FrameBuilder builder = setup.builder();
  builder.observe(simulation);
  const render::DrawList list = builder.build(simulation);

  // The arrows' tails (the centre) are in view, their unscaled tips (1.1 and 1.2 bounding
  // radii of a ~1.6 m box) are not: the fit must shrink them, and say so.
  ASSERT_FALSE(list.arrows.empty());
  for (const render::Arrow& arrow : list.arrows) {
    const Eigen::Vector3f tip =
        render::project_to_pixels(list.camera, kArrowFitWidth, kArrowFitHeight, arrow.to);
    EXPECT_GT(tip.z(), 0.0f);
    EXPECT_GE(tip.x(), 0.0f);
    EXPECT_LE(tip.x(), static_cast<float>(kArrowFitWidth));
    EXPECT_GE(tip.y(), 0.0f);
    EXPECT_LE(tip.y(), static_cast<float>(kArrowFitHeight));
  }
  // The L arrow still points along L.
  const Eigen::Vector3f momentum =
      setup.scene.initial[0].angular_momentum.cast<float>().normalized();
  bool along_l = false;
  for (const render::Arrow& arrow : list.arrows) {
    along_l = along_l || (arrow.to - arrow.from).normalized().dot(momentum) > 0.9999f;
  }
  EXPECT_TRUE(along_l);
  bool stated = false;
  for (const render::Label& label : list.labels) {
    stated = stated || label.text.find("arrows drawn at 0.") != std::string::npos;
  }
  EXPECT_TRUE(stated) << "the shrink factor is stated in the frame";
}

}  // namespace
}  // namespace tumble::app
