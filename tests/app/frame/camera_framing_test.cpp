// The automatic framing keeps the bodies large: in every demo scene, and in a body thrown
// under gravity, each body's projected size (the larger of its width and height on screen) is
// at least a third of the frame's height at every frame of the whole video, and the body stays
// inside the frame.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>

#include "app/frame/frame_builder.hpp"
#include "engine/geometry/primitive_meshes.hpp"
#include "render/camera_math.hpp"

namespace tumble::app {
namespace {

render::Renderer& framing_renderer() {
  static render::Renderer renderer(render::RendererOptions{32, 24, 1});
  return renderer;
}

/// Projected size of every body (the larger of its width and height on screen) as a fraction
/// of the frame height, the smallest over the video's frames; fails the test when a body
/// leaves the frame.
double smallest_height_fraction(const std::string& text, const std::string& path) {
  const SceneDescription description = parse_scene(text, path);
  const CompiledScene scene = compile_scene(description, true);
  std::vector<std::string> names;
  for (const auto& body : description.bodies) names.push_back(body.name);
  const RenderSettings settings =
      parse_render_settings(description.render.value_or(nlohmann::json::object()), path, names);
  // Body-frame points of each drawn body (its mesh, or its equivalent box's corners).
  std::vector<std::vector<Eigen::Vector3d>> points(scene.bodies.size());
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const engine::BodyModel& body = scene.bodies[i];
    if (i < scene.geometry.size() && scene.geometry[i]) {
      const auto& positions = scene.geometry[i]->positions;
      const std::size_t stride = std::max<std::size_t>(1, positions.size() / 400);
      for (std::size_t k = 0; k < positions.size(); k += stride) points[i].push_back(positions[k]);
    } else {
      const Eigen::Vector3d half = 0.5 * equivalent_box_size(body.mass, body.moments);
      for (int c = 0; c < 8; ++c) {
        points[i].push_back(body.principal_to_body * Eigen::Vector3d(c & 1 ? half.x() : -half.x(),
                                                                     c & 2 ? half.y() : -half.y(),
                                                                     c & 4 ? half.z() : -half.z()));
      }
    }
  }
  engine::Simulation simulation(scene.bodies, scene.initial, scene.settings);
  FrameBuilder builder(description, scene, settings, framing_renderer());
  const double step = settings.time_scale / settings.fps;
  const double dt = scene.settings.dt;
  double smallest = 1.0;
  for (int frame = 0; frame * step <= scene.settings.duration + 1e-9; ++frame) {
    while (!simulation.finished() && simulation.time() + 0.5 * dt <= frame * step) {
      simulation.step();
    }
    builder.observe(simulation);
    const render::Camera camera = builder.build(simulation).camera;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const engine::BodyState& state = simulation.states()[i];
      const Eigen::Quaterniond orientation =
          engine::body_orientation(simulation.bodies()[i], state);
      Eigen::Vector2f low = Eigen::Vector2f::Constant(1e30f);
      Eigen::Vector2f high = -low;
      for (const Eigen::Vector3d& p : points[i]) {
        const Eigen::Vector3d world = state.position + orientation * p;
        const Eigen::Vector3f pixel =
            render::project_to_pixels(camera, settings.width, settings.height, world.cast<float>());
        const bool inside = pixel.x() >= 0.0f && pixel.x() <= static_cast<float>(settings.width) &&
                            pixel.y() >= 0.0f && pixel.y() <= static_cast<float>(settings.height);
        if (!inside) {
          ADD_FAILURE() << path << " frame " << frame << " body " << i << " leaves the frame at "
                        << pixel.transpose();
          return 0.0;
        }
        low = low.cwiseMin(pixel.head<2>());
        high = high.cwiseMax(pixel.head<2>());
      }
      // Its size on screen: the larger of its projected width and height (a flat body seen
      // edge-on is short but wide).
      smallest = std::min(smallest, static_cast<double>((high - low).maxCoeff()) / settings.height);
    }
  }
  return smallest;
}

std::string read(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(CameraFraming, EveryDemoSceneKeepsItsBodiesAThirdOfTheFrameHigh) {
  const std::filesystem::path folder = std::filesystem::path(TUMBLE_SOURCE_DIR) / "assets/scenes";
  int scenes = 0;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (entry.path().extension() != ".json") continue;
    ++scenes;
    const double fraction = smallest_height_fraction(read(entry.path()), entry.path().string());
    std::printf("[ framing  ] %s: smallest body %.3f of the frame height\n",
                entry.path().filename().c_str(), fraction);
    EXPECT_GE(fraction, 1.0 / 3.0) << entry.path().filename();
  }
  EXPECT_GE(scenes, 8);
}

TEST(CameraFraming, ABodyThrownUnderGravityStaysAThirdOfTheFrameHigh) {
  const std::string text = R"({"duration": 3, "dt": 0.002, "gravity": [0, 0, -9.81],
    "bodies": [{"name": "brick", "shape": {"box": [0.3, 0.2, 0.1]}, "mass": 1,
      "velocity": [2, 0.5, 12], "angular_velocity": [1, 4, 0.5]}]})";
  const std::string path = std::string(TUMBLE_SOURCE_DIR) + "/assets/scenes/thrown.json";
  EXPECT_GE(smallest_height_fraction(text, path), 1.0 / 3.0);
}

// The coin demo shows its precession clearly: the symmetry axis turns about L on a cone whose
// half-angle, constant for a torque-free symmetric body, is cos(theta) = I3 w3 / |L|
// (Landau & Lifshitz, Mechanics, section 33) with I3 the moment about the symmetry axis. It
// is checked against the simulated run at its end.
TEST(CameraFraming, CoinDemoPrecessesOnAWideCone) {
  const std::string path = std::string(TUMBLE_SOURCE_DIR) + "/assets/scenes/coin_precession.json";
  const SceneDescription description = parse_scene(read(path), path);
  const CompiledScene scene = compile_scene(description, true);
  const engine::BodyModel& coin = scene.bodies[0];
  const Eigen::Vector3d moments = coin.moments;
  // The symmetry axis: the principal axis whose moment differs from the other two.
  Eigen::Index axis = 0;
  for (Eigen::Index k = 0; k < 3; ++k) {
    const double a = moments((k + 1) % 3);
    const double b = moments((k + 2) % 3);
    if (std::abs(a - b) < 1e-6 * moments.maxCoeff()) axis = k;
  }
  const Eigen::Vector3d omega_principal =
      scene.initial[0].orientation.inverse() * engine::angular_velocity(coin, scene.initial[0]);
  const double closed_form = std::acos(moments(axis) * std::abs(omega_principal(axis)) /
                                       (moments.asDiagonal() * omega_principal).norm());
  EXPECT_GE(closed_form * 180.0 / std::numbers::pi, 20.0);
  engine::Simulation simulation(scene.bodies, scene.initial, scene.settings);
  while (!simulation.finished()) simulation.step();
  const engine::BodyState& end = simulation.states()[0];
  const Eigen::Vector3d symmetry = end.orientation * Eigen::Vector3d::Unit(axis);
  const double simulated = std::acos(std::abs(symmetry.dot(end.angular_momentum.normalized())));
  EXPECT_NEAR(simulated, closed_form, 1e-3);
  std::cout << "coin cone half-angle " << closed_form * 180.0 / std::numbers::pi << " deg\n";
}

}  // namespace
}  // namespace tumble::app
