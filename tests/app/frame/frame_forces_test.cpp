// Springs and pivots drawn by the frame builder (app/frame/src/frame_forces.cpp): the coil runs
// from the anchor to the attachment point and stretches with it, and it shows in the pixels;
// a pivot has a marker at the pivot and a stem away from the hanging body.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <nlohmann/json.hpp>
#include <utility>

#include "app/frame/frame_builder.hpp"
#include "frame_scene_setup.hpp"
#include "render/camera_math.hpp"

namespace tumble::app {
namespace {

constexpr int kFrameForcesWidth = 160;
constexpr int kFrameForcesHeight = 120;

render::Renderer& forces_renderer() {
  return testing::frame_test_renderer(kFrameForcesWidth, kFrameForcesHeight);
}

/// A scene drawn at this file's frame size.
struct ForcesScene : testing::FrameSceneSetup {
  explicit ForcesScene(const std::string& text)
      : FrameSceneSetup(text, kFrameForcesWidth, kFrameForcesHeight) {}
};

void frame_forces_advance_to(engine::Simulation& simulation, double time) {
  const double dt = simulation.settings().dt;
  while (!simulation.finished() && simulation.time() + 0.5 * dt <= time) simulation.step();
}

/// The polylines drawn in the spring colour (red, little green or blue).
std::vector<const render::Polyline*> coils(const render::DrawList& list) {
  std::vector<const render::Polyline*> found;
  for (const render::Polyline& line : list.polylines) {
    if (line.colour.r > 0.8f && line.colour.g < 0.4f && line.colour.b < 0.4f) {
      found.push_back(&line);
    }
  }
  return found;
}

// A cube on a vertical spring under gravity, released at rest above its equilibrium:
// it falls straight down without turning (the spring's line runs through the centre of mass),
// so the attachment point is the centre of mass plus 0.1 m up at every instant.
const char* kHangingCube = R"({"duration": 1, "dt": 0.002, "gravity": [0, 0, -9.81],
  "bodies": [{"name": "cube", "shape": {"box": [0.2, 0.2, 0.2]}, "mass": 1,
    "position": [0, 0, 0.3],
    "spring": {"anchor": [0, 0, 0.5], "attach": [0, 0, 0.1], "stiffness": 20, "damping": 0}}],
  "render": {"show": {"overlay": false, "angular_velocity": false, "angular_momentum": false}}})";

TEST(FrameForces, SpringCoilRunsFromAnchorToAttachmentAndStretches) {
  const ForcesScene setup(kHangingCube);
  engine::Simulation simulation(setup.scene.bodies, setup.scene.initial, setup.scene.settings);
  FrameBuilder builder(setup.description, setup.scene, setup.settings, forces_renderer());
  const Eigen::Vector3d anchor(0, 0, 0.5);
  double first_length = 0.0;
  for (const double time : {0.0, 0.7025}) {
    frame_forces_advance_to(simulation, time);
    builder.observe(simulation);
    const render::DrawList list = builder.build(simulation);
    const auto found = coils(list);
    ASSERT_EQ(found.size(), 1u) << "t = " << time;
    const std::vector<Eigen::Vector3f>& points = found.front()->points;
    const Eigen::Vector3d attach = simulation.states()[0].position + Eigen::Vector3d(0, 0, 0.1);
    EXPECT_LT((points.front().cast<double>() - anchor).norm(), 1e-6) << "t = " << time;
    EXPECT_LT((points.back().cast<double>() - attach).norm(), 1e-6) << "t = " << time;
    // Every point of the coil lies between the two ends along the spring's line.
    for (const Eigen::Vector3f& p : points) {
      EXPECT_LE(p.z(), anchor.z() + 1e-6);
      EXPECT_GE(p.z(), attach.z() - 1e-6);
    }
    if (time == 0.0) {
      first_length = (anchor - attach).norm();
    } else {
      // Half a period pi sqrt(m / k) later it is at the bottom of its swing, as far below the
      // equilibrium (a zero-length spring stretched by m g / k) as it started above it.
      EXPECT_NEAR((anchor - attach).norm(), 2.0 * 9.81 / 20.0 - first_length, 0.02);
    }
  }
}

TEST(FrameForces, SpringCoilIsInThePixelsAlongItsLength) {
  const ForcesScene setup(kHangingCube);
  engine::Simulation simulation(setup.scene.bodies, setup.scene.initial, setup.scene.settings);
  FrameBuilder builder(setup.description, setup.scene, setup.settings, forces_renderer());
  builder.observe(simulation);
  const render::DrawList list = builder.build(simulation);
  const tumble::Image image = forces_renderer().render(list);
  const auto found = coils(list);
  ASSERT_EQ(found.size(), 1u);
  const std::vector<Eigen::Vector3f>& points = found.front()->points;
  // Near each of five points spread along the coil, a pixel of the spring's red.
  for (int k = 0; k <= 4; ++k) {
    const Eigen::Vector3f world = points[(points.size() - 1) * static_cast<std::size_t>(k) / 4];
    const Eigen::Vector3f pixel =
        render::project_to_pixels(list.camera, kFrameForcesWidth, kFrameForcesHeight, world);
    ASSERT_GT(pixel.x(), 0.0f);
    ASSERT_LT(pixel.x(), kFrameForcesWidth);
    ASSERT_GT(pixel.y(), 0.0f);
    ASSERT_LT(pixel.y(), kFrameForcesHeight);
    bool red = false;
    for (int dy = -2; dy <= 2; ++dy) {
      for (int dx = -2; dx <= 2; ++dx) {
        const int x = std::clamp(static_cast<int>(pixel.x()) + dx, 0, kFrameForcesWidth - 1);
        const int y = std::clamp(static_cast<int>(pixel.y()) + dy, 0, kFrameForcesHeight - 1);
        const std::uint8_t* rgba = image.pixel(x, y);
        red = red || (rgba[0] > 150 && rgba[1] < 0.5 * rgba[0] && rgba[2] < 0.5 * rgba[0]);
      }
    }
    EXPECT_TRUE(red) << "coil point " << k << " at pixel " << pixel.transpose();
  }
}

// A cube hanging from a pivot 0.5 m above its centre of mass.
TEST(FrameForces, PivotHasAMarkerAndAStemUpFromAHangingBody) {
  const ForcesScene setup(R"({"duration": 1, "dt": 0.002, "gravity": [0, 0, -9.81],
    "bodies": [{"name": "cube", "shape": {"box": [0.2, 0.2, 0.2]}, "mass": 1,
      "pivot": [0, 0, 0.5], "angular_velocity": [1, 0, 0]}],
    "render": {"show": {"overlay": false}}})");
  engine::Simulation simulation(setup.scene.bodies, setup.scene.initial, setup.scene.settings);
  FrameBuilder builder(setup.description, setup.scene, setup.settings, forces_renderer());
  frame_forces_advance_to(simulation, 0.4);
  builder.observe(simulation);
  const render::DrawList list = builder.build(simulation);
  const Eigen::Vector3f pivot(0, 0, 0.5);
  bool marker = false;
  for (const render::Points& points : list.points) {
    for (const Eigen::Vector3f& p : points.positions) marker = marker || (p - pivot).norm() < 1e-6;
  }
  EXPECT_TRUE(marker);
  // A stem from the pivot straight up, and a link from the pivot to the swinging centre of mass.
  bool stem = false;
  bool link = false;
  const Eigen::Vector3f com = simulation.states()[0].position.cast<float>();
  EXPECT_GT((com - Eigen::Vector3f(0, 0, 0)).norm(), 1e-3f);  // it swung
  for (const render::Polyline& line : list.polylines) {
    if (line.points.size() != 2 || (line.points.front() - pivot).norm() > 1e-6f) continue;
    const Eigen::Vector3f span = line.points.back() - pivot;
    stem = stem || (span.normalized() - Eigen::Vector3f::UnitZ()).norm() < 1e-5f;
    link = link || (line.points.back() - com).norm() < 1e-6f;
  }
  EXPECT_TRUE(stem);
  EXPECT_TRUE(link);
}

// The marker's diameter against the frame height it is laid out for: 3% of it (9 px at least),
// so its share of the frame's area stays the same from 720p to 2160p and a small GIF still
// shows a 9 px dot (a fixed 9 px dot was 0.007% of a 720p frame and 0.0008% of a 2160p one).
TEST(FrameForces, PivotMarkerKeepsItsShareOfTheFrameAtEverySize) {
  const ForcesScene setup(R"({"duration": 1, "dt": 0.002, "gravity": [0, 0, -9.81],
    "bodies": [{"name": "cube", "shape": {"box": [0.2, 0.2, 0.2]}, "mass": 1,
      "pivot": [0, 0, 0.5]}],
    "render": {"show": {"overlay": false}}})");
  engine::Simulation simulation(setup.scene.bodies, setup.scene.initial, setup.scene.settings);
  FrameBuilder builder(setup.description, setup.scene, setup.settings, forces_renderer());
  builder.observe(simulation);
  const Eigen::Vector3f pivot(0, 0, 0.5);
  for (const auto& [width, height] : {std::pair{480, 270}, {1280, 720}, {3840, 2160}}) {
    builder.set_frame(width, height, 1.0);
    const render::DrawList list = builder.build(simulation);
    float diameter = 0.0f;
    for (const render::Points& points : list.points) {
      if (points.positions.size() == 1 && (points.positions[0] - pivot).norm() < 1e-6f) {
        diameter = points.size_px;
      }
    }
    const float expected = std::max(9.0f, 0.03f * static_cast<float>(height));
    EXPECT_FLOAT_EQ(diameter, expected) << width << "x" << height;
    // Its disc covers pi / 4 x 0.03^2 x 9 / 16 = 0.0398% of a 16:9 frame from 720 lines up.
    const double share = 0.25 * 3.14159265 * diameter * diameter / (double(width) * height);
    if (height >= 720) {
      EXPECT_GT(share, 3.9e-4) << width << "x" << height;
    }
  }
}

}  // namespace
}  // namespace tumble::app
