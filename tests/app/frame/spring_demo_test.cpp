// The spring demo (assets/scenes/racket_on_spring.json): a tennis racket hung on a spring
// hooked at its centre of mass, bouncing and swinging while it flips about its intermediate
// axis. A spring through the centre of mass exerts no torque about it, so
// - the centre of mass moves as an isotropic harmonic oscillator about the equilibrium
//   q = anchor + m g / k (the spring has zero rest length): x(t) = q + (x0 - q) cos(wn t) +
//   (v0 / wn) sin(wn t), wn = sqrt(k / m), period 2 pi sqrt(m / k), whatever the tumbling;
// - the rotation is that of the free racket (the same integrator without spring or gravity);
// - and the coil is drawn, in the frames of the video, from the anchor to the racket.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <sstream>
#include <variant>

#include "app/frame/frame_builder.hpp"
#include "frame_scene_setup.hpp"
#include "render/camera_math.hpp"

namespace tumble::app {
namespace {

const std::string kPath = std::string(TUMBLE_SOURCE_DIR) + "/assets/scenes/racket_on_spring.json";

std::string demo_text() {
  std::ifstream in(kPath);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

CompiledScene compile(const std::string& text) {
  return compile_scene(parse_scene(text, kPath), false);
}

const engine::Spring& spring_of(const engine::BodyModel& body) {
  for (const engine::ForceTerm& term : body.forces) {
    if (const auto* spring = std::get_if<engine::Spring>(&term)) return *spring;
  }
  throw std::logic_error("the demo's body has no spring");
}

TEST(SpringDemo, CentreOfMassOscillatesWithThePeriodOfItsSpring) {
  const CompiledScene scene = compile(demo_text());
  const engine::BodyModel& racket = scene.bodies.at(0);
  const engine::Spring& spring = spring_of(racket);
  EXPECT_TRUE(spring.attach.isZero());
  const double m = racket.mass;
  const double k = spring.stiffness;
  const double wn = std::sqrt(k / m);
  const Eigen::Vector3d g(0, 0, -9.81);
  const Eigen::Vector3d q = spring.anchor + m * g / k;
  const Eigen::Vector3d x0 = scene.initial[0].position - q;
  const Eigen::Vector3d v0 = scene.initial[0].velocity;
  engine::Simulation simulation(scene.bodies, scene.initial, scene.settings);
  // Upward crossings of the equilibrium's height, interpolated linearly between steps.
  std::vector<double> crossings;
  double largest_error = 0.0;
  double previous = simulation.states()[0].position.z() - q.z();
  while (!simulation.finished()) {
    const double t0 = simulation.time();
    simulation.step();
    const double t = simulation.time();
    const Eigen::Vector3d x = simulation.states()[0].position;
    const Eigen::Vector3d closed = q + x0 * std::cos(wn * t) + v0 / wn * std::sin(wn * t);
    largest_error = std::max(largest_error, (x - closed).norm());
    const double now = x.z() - q.z();
    if (previous < 0.0 && now >= 0.0)
      crossings.push_back(t0 + (t - t0) * previous / (previous - now));
    previous = now;
  }
  ASSERT_GE(crossings.size(), 4u);
  const double measured =
      (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  const double period = 2.0 * std::numbers::pi * std::sqrt(m / k);
  std::printf(
      "[ spring   ] period %.6f s measured over %zu cycles, closed form %.6f s; "
      "largest distance from the closed-form orbit %.2e m\n",
      measured, crossings.size() - 1, period, largest_error);
  EXPECT_NEAR(measured / period, 1.0, 0.01);
  EXPECT_LT(largest_error, 1e-6 * x0.norm() + 1e-9);
  // It swings, too: the orbit is an ellipse, not a vertical line.
  EXPECT_GT(v0.norm() / wn, 0.05);
}

TEST(SpringDemo, RacketTumblesAsIfFree) {
  const std::string text = demo_text();
  nlohmann::json free = nlohmann::json::parse(text, nullptr, true, true);
  free.erase("gravity");
  free["bodies"][0].erase("spring");
  const CompiledScene hung = compile(text);
  const CompiledScene alone = compile(free.dump());
  engine::Simulation a(hung.bodies, hung.initial, hung.settings);
  engine::Simulation b(alone.bodies, alone.initial, alone.settings);
  // The spin axis (body x, the intermediate axis) against the fixed L: it starts along L
  // and the flip turns it over.
  const Eigen::Vector3d momentum = a.states()[0].angular_momentum.normalized();
  double lowest = 1.0;
  double largest_angle = 0.0;
  while (!a.finished()) {
    a.step();
    b.step();
    const Eigen::Quaterniond qa = engine::body_orientation(a.bodies()[0], a.states()[0]);
    const Eigen::Quaterniond qb = engine::body_orientation(b.bodies()[0], b.states()[0]);
    largest_angle = std::max(largest_angle, qa.angularDistance(qb));
    lowest = std::min(lowest, (qa * Eigen::Vector3d::UnitX()).dot(momentum));
  }
  EXPECT_LT(largest_angle, 1e-9);
  EXPECT_LT((a.states()[0].angular_momentum.normalized() - momentum).norm(), 1e-9);
  EXPECT_LT(lowest, -0.9);
}

/// The polyline drawn in the spring colour (red, little green or blue).
const render::Polyline* coil(const render::DrawList& list) {
  for (const render::Polyline& line : list.polylines) {
    if (line.colour.r > 0.8f && line.colour.g < 0.4f && line.colour.b < 0.4f) return &line;
  }
  return nullptr;
}

// In frames of the video, the coil's red is in the pixels along the coil from the anchor to
// the racket: near every sampled coil point outside the racket's bounding ball (which the
// racket could hide) and off the arrows.
TEST(SpringDemo, CoilIsDrawnBetweenAnchorAndRacket) {
  constexpr int kSpringDemoWidth = 320;
  constexpr int kSpringDemoHeight = 180;
  const testing::FrameSceneSetup setup(demo_text(), kSpringDemoWidth, kSpringDemoHeight);
  engine::Simulation simulation = setup.simulation();
  FrameBuilder builder = setup.builder();
  // The racket's bounding radius about its centre of mass (its mesh is in the body frame).
  double radius = 0.0;
  for (const Eigen::Vector3d& p : setup.scene.geometry.at(0)->positions) {
    radius = std::max(radius, p.norm());
  }
  ASSERT_GT(radius, 0.1);
  int sampled = 0;
  int red = 0;
  int frames = 0;
  for (const double time : {0.0, 1.0, 2.5, 4.0, 6.0}) {
    while (simulation.time() + 0.5 * setup.scene.settings.dt <= time) simulation.step();
    builder.observe(simulation);
    render::DrawList list = builder.build(simulation);
    // Only the coil is looked for: no arrows that could cross it, no overlay over it.
    list.arrows.clear();
    list.panels.clear();
    list.labels.clear();
    const render::Polyline* found = coil(list);
    ASSERT_NE(found, nullptr) << "t = " << time;
    const tumble::Image image = setup.renderer().render(list);
    const Eigen::Vector3d centre = simulation.states()[0].position;
    int frame_red = 0;
    for (std::size_t i = 0; i < found->points.size(); i += 8) {
      const Eigen::Vector3f world = found->points[i];
      if ((world.cast<double>() - centre).norm() < radius) continue;
      const Eigen::Vector3f pixel =
          render::project_to_pixels(list.camera, kSpringDemoWidth, kSpringDemoHeight, world);
      ++sampled;
      bool here = false;
      for (int dy = -2; dy <= 2; ++dy) {
        for (int dx = -2; dx <= 2; ++dx) {
          const int x = std::clamp(static_cast<int>(pixel.x()) + dx, 0, kSpringDemoWidth - 1);
          const int y = std::clamp(static_cast<int>(pixel.y()) + dy, 0, kSpringDemoHeight - 1);
          const std::uint8_t* rgba = image.pixel(x, y);
          here = here || (rgba[0] > 150 && rgba[1] < 0.5 * rgba[0] && rgba[2] < 0.5 * rgba[0]);
        }
      }
      frame_red += here ? 1 : 0;
    }
    red += frame_red;
    frames += frame_red > 0 ? 1 : 0;
  }
  std::printf("[ spring   ] coil red near %d of %d sampled points outside the racket\n", red,
              sampled);
  EXPECT_EQ(frames, 5);  // every frame shows its coil
  EXPECT_GE(sampled, 20);
  EXPECT_GE(red, 0.9 * sampled);
}

}  // namespace
}  // namespace tumble::app
