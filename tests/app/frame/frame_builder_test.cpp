#include "app/frame/frame_builder.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>

#include "engine/geometry/primitive_meshes.hpp"
#include "engine/mass/mass_properties.hpp"
#include "frame_scene_setup.hpp"
#include "render/camera_math.hpp"
#include "support/scene_builder.hpp"

namespace tumble::app {
namespace {

using ::testing::HasSubstr;

constexpr int kFrameBuilderWidth = 64;
constexpr int kFrameBuilderHeight = 48;

/// A scene drawn at the tests' frame size.
struct SceneSetup : testing::FrameSceneSetup {
  explicit SceneSetup(const std::string& text)
      : FrameSceneSetup(text, kFrameBuilderWidth, kFrameBuilderHeight) {}
};

/// An asymmetric brick spinning near its middle axis (it flips), given by its inertia only.
std::string brick_scene(const std::string& render, const std::string& integrator = "rk4") {
  return testing::SceneBuilder()
      .duration(6)
      .dt(0.002)
      .integrator(integrator)
      .body(testing::BodyBuilder("brick")
                .principal({0.4, 0.9, 1.1})
                .mass(2)
                .orientation(0.9, 0.2, -0.3, 0.1)
                .angular_velocity({0.05, 3.0, 0.1}, "body"))
      .render(nlohmann::json::parse(render))
      .text();
}

/// Advances to the frame time `time` (the last step at or before it).
void frame_builder_advance_to(engine::Simulation& simulation, double time) {
  const double dt = simulation.settings().dt;
  while (!simulation.finished() && simulation.time() + 0.5 * dt <= time) simulation.step();
}

Eigen::Vector3d to_double(const Eigen::Vector3f& v) {
  return v.cast<double>();
}

// --- Arrows -------------------------------------------------------------------------------

TEST(FrameBuilder, OmegaAndMomentumArrowsPointAlongTheState) {
  const SceneSetup setup(brick_scene(R"({"show": {"overlay": false}})"));
  engine::Simulation simulation = setup.simulation();
  FrameBuilder builder = setup.builder();
  for (int frame = 0; frame <= 90; ++frame) {
    frame_builder_advance_to(simulation, frame / 30.0);
    builder.observe(simulation);
    if (frame % 15 != 0) continue;
    const render::DrawList list = builder.build(simulation);
    ASSERT_EQ(list.arrows.size(), 2u);
    const engine::BodyModel& body = simulation.bodies()[0];
    const engine::BodyState& state = simulation.states()[0];
    const Eigen::Vector3d omega = engine::angular_velocity(body, state);
    const Eigen::Vector3d omega_arrow = to_double(list.arrows[0].to - list.arrows[0].from);
    const Eigen::Vector3d momentum_arrow = to_double(list.arrows[1].to - list.arrows[1].from);
    EXPECT_LT((omega_arrow.normalized() - omega.normalized()).norm(), 1e-6) << frame;
    EXPECT_LT((momentum_arrow.normalized() - state.angular_momentum.normalized()).norm(), 1e-6);
    // Both start at the rotation centre (the centre of mass of this free body).
    EXPECT_LT((to_double(list.arrows[0].from) - state.position).norm(), 1e-6);
  }
}

TEST(FrameBuilder, MomentumArrowStaysFixedForATorqueFreeBody) {
  const SceneSetup setup(brick_scene(R"({"show": {"angular_velocity": false, "overlay": false}})"));
  engine::Simulation simulation = setup.simulation();
  FrameBuilder builder = setup.builder();
  builder.observe(simulation);
  const render::Arrow first = builder.build(simulation).arrows.at(0);
  const float length = (first.to - first.from).norm();
  EXPECT_GT(length, 0.0f);
  double omega_change = 0.0;
  for (int frame = 1; frame <= 120; ++frame) {
    frame_builder_advance_to(simulation, frame / 20.0);
    builder.observe(simulation);
    const render::Arrow arrow = builder.build(simulation).arrows.at(0);
    // The same arrow to float precision (L is exactly conserved by RK4 for a free body).
    EXPECT_LT((arrow.from - first.from).norm(), 1e-6f * length) << frame;
    EXPECT_LT((arrow.to - first.to).norm(), 1e-6f * length) << frame;
    omega_change =
        std::max(omega_change,
                 (engine::angular_velocity(simulation.bodies()[0], simulation.states()[0]) -
                  engine::angular_velocity(simulation.bodies()[0], simulation.initial_states()[0]))
                     .norm());
  }
  // Meanwhile w did move a lot (the brick flips), so the check above is not vacuous.
  EXPECT_GT(omega_change, 1.0);
}

TEST(FrameBuilder, BodyAndPrincipalAxesFollowTheOrientation) {
  const SceneSetup setup(brick_scene(
      R"({"show": {"angular_velocity": false, "angular_momentum": false, "body_axes": true,
                   "principal_axes": true, "overlay": false}})"));
  engine::Simulation simulation = setup.simulation();
  frame_builder_advance_to(simulation, 1.3);
  FrameBuilder builder = setup.builder();
  builder.observe(simulation);
  const render::DrawList list = builder.build(simulation);
  ASSERT_EQ(list.arrows.size(), 6u);
  const engine::BodyModel& body = simulation.bodies()[0];
  const engine::BodyState& state = simulation.states()[0];
  const Eigen::Matrix3d body_axes = engine::body_orientation(body, state).toRotationMatrix();
  const Eigen::Matrix3d principal_axes = state.orientation.toRotationMatrix();
  std::vector<double> lengths;
  for (int a = 0; a < 3; ++a) {
    const Eigen::Vector3d drawn = to_double(list.arrows[a].to - list.arrows[a].from);
    EXPECT_LT((drawn.normalized() - body_axes.col(a)).norm(), 1e-6);
    const Eigen::Vector3d principal = to_double(list.arrows[a + 3].to - list.arrows[a + 3].from);
    EXPECT_LT((principal.normalized() - principal_axes.col(a)).norm(), 1e-6);
    lengths.push_back(principal.norm());
  }
  // Principal axes scaled by the moments.
  EXPECT_NEAR(lengths[0] / lengths[2], body.moments[0] / body.moments[2], 1e-6);
  EXPECT_NEAR(lengths[1] / lengths[2], body.moments[1] / body.moments[2], 1e-6);
}

// --- Meshes -------------------------------------------------------------------------------

TEST(FrameBuilder, EquivalentBoxHasTheSameMassAndMoments) {
  const double mass = 2.5;
  for (const Eigen::Vector3d& moments :
       {Eigen::Vector3d(0.4, 0.9, 1.1), Eigen::Vector3d(1, 1, 1), Eigen::Vector3d(0.01, 2, 2.005),
        Eigen::Vector3d(3e-4, 5e-4, 7e-4)}) {
    const Eigen::Vector3d size = equivalent_box_size(mass, moments);
    const engine::TriangleMesh box = engine::box_mesh(size);
    const engine::MomentIntegrals integrals = engine::solid_integrals(box, Eigen::Vector3d::Zero());
    const engine::MassProperties properties =
        engine::mass_properties(integrals, Eigen::Vector3d::Zero(), mass / integrals.measure);
    EXPECT_NEAR(properties.mass, mass, 1e-12 * mass);
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(properties.inertia(i, i), moments[i], 1e-12 * moments.maxCoeff()) << moments;
      for (int j = 0; j < 3; ++j) {
        if (j != i) {
          EXPECT_NEAR(properties.inertia(i, j), 0.0, 1e-12 * moments.maxCoeff());
        }
      }
    }
  }
}

TEST(FrameBuilder, BodyPoseIsCentreOfMassAndBodyOrientation) {
  const SceneSetup setup(
      R"({"duration": 2, "dt": 0.001, "bodies": [{"name": "t",
          "mesh": "../meshes/t_handle.obj", "density": 2700, "position": [0.3, -0.2, 1.0],
          "velocity": [0.1, 0, 0], "angular_velocity": [0.05, 10, 0.05],
          "angular_velocity_frame": "body"}]})");
  engine::Simulation simulation = setup.simulation();
  frame_builder_advance_to(simulation, 0.77);
  FrameBuilder builder = setup.builder();
  builder.observe(simulation);
  const render::DrawList list = builder.build(simulation);
  ASSERT_EQ(list.meshes.size(), 1u);
  const engine::BodyState& state = simulation.states()[0];
  Eigen::Affine3d expected = Eigen::Translation3d(state.position) *
                             engine::body_orientation(simulation.bodies()[0], state);
  EXPECT_LT((list.meshes[0].pose.cast<double>() - expected.matrix()).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_EQ(list.meshes[0].colour.a, 1.0f);
}

// --- Poinsot curves -----------------------------------------------------------------------

/// Runs the brick with `show` items, observing 30 frames per second, and builds the last frame.
struct PoinsotRun {
  engine::Simulation simulation;
  render::DrawList list;
};

/// `width` x `height`: the frame the overlay is laid out for (the draw list is not rendered).
PoinsotRun run_brick(const std::string& render, const std::string& integrator = "rk4",
                     int width = kFrameBuilderWidth, int height = kFrameBuilderHeight) {
  SceneSetup setup(brick_scene(render, integrator));
  setup.settings.width = width;
  setup.settings.height = height;
  PoinsotRun run{setup.simulation(), {}};
  FrameBuilder builder = setup.builder();
  for (int frame = 0; frame <= 180; ++frame) {
    frame_builder_advance_to(run.simulation, frame / 30.0);
    builder.observe(run.simulation);
  }
  run.list = builder.build(run.simulation);
  return run;
}

TEST(FrameBuilder, HerpolhodeLiesInTheInvariablePlane) {
  const PoinsotRun run =
      run_brick(R"({"show": {"angular_momentum": false, "herpolhode": true, "overlay": false}})");
  const engine::BodyModel& body = run.simulation.bodies()[0];
  const engine::BodyState& start = run.simulation.initial_states()[0];
  ASSERT_EQ(run.list.polylines.size(), 1u);
  ASSERT_EQ(run.list.arrows.size(), 1u);
  // Scale of the drawn w (arrow length / |w|) and the plane's distance s 2T / |L|.
  const engine::BodyState& state = run.simulation.states()[0];
  const Eigen::Vector3d omega = engine::angular_velocity(body, state);
  const render::Arrow& arrow = run.list.arrows[0];
  const double scale = to_double(arrow.to - arrow.from).norm() / omega.norm();
  const Eigen::Vector3d normal = start.angular_momentum.normalized();
  const double twice_kinetic = engine::angular_velocity(body, start).dot(start.angular_momentum);
  const double plane = scale * twice_kinetic / start.angular_momentum.norm();
  const std::vector<Eigen::Vector3f>& points = run.list.polylines[0].points;
  ASSERT_EQ(points.size(), 181u);
  double spread = 0.0;
  for (const Eigen::Vector3f& p : points) {
    const double height = (to_double(p) - state.position).dot(normal);
    spread = std::max(spread, std::abs(height - plane));
  }
  EXPECT_LT(spread, 1e-5 * plane);
  // The curve is not a point: the tip wanders far within the plane during the flip.
  EXPECT_GT((points.front() - points[points.size() / 2]).norm(), 0.3f * arrow.thickness);
}

TEST(FrameBuilder, PolhodeLiesOnTheEnergyEllipsoidAndMomentumSphere) {
  const PoinsotRun run =
      run_brick(R"({"show": {"angular_momentum": false, "polhode": true, "overlay": false}})");
  const engine::BodyModel& body = run.simulation.bodies()[0];
  const engine::BodyState& start = run.simulation.initial_states()[0];
  const engine::BodyState& state = run.simulation.states()[0];
  ASSERT_EQ(run.list.polylines.size(), 1u);
  const double scale = to_double(run.list.arrows.at(0).to - run.list.arrows.at(0).from).norm() /
                       engine::angular_velocity(body, state).norm();
  const double twice_kinetic = engine::angular_velocity(body, start).dot(start.angular_momentum);
  const double momentum_squared = start.angular_momentum.squaredNorm();
  const Eigen::Vector3d& moments = body.moments;
  Eigen::Vector3d low = Eigen::Vector3d::Constant(1e9);
  Eigen::Vector3d high = -low;
  for (const Eigen::Vector3f& p : run.list.polylines[0].points) {
    // Back into the principal frame: w = R^T (p - centre) / s.
    const Eigen::Vector3d w = state.orientation.inverse() * (to_double(p) - state.position) / scale;
    EXPECT_NEAR(w.dot(moments.asDiagonal() * w), twice_kinetic, 1e-5 * twice_kinetic);
    EXPECT_NEAR((moments.asDiagonal() * w).squaredNorm(), momentum_squared,
                1e-5 * momentum_squared);
    low = low.cwiseMin(w);
    high = high.cwiseMax(w);
  }
  // Around the middle axis: w2 changes sign over the run (the flip).
  EXPECT_LT(low[1], 0.0);
  EXPECT_GT(high[1], 0.0);
}

TEST(FrameBuilder, InertiaEllipsoidMovesWithTheBodyAndIsTranslucent) {
  const PoinsotRun run = run_brick(R"({"show": {"inertia_ellipsoid": true, "overlay": false}})");
  ASSERT_EQ(run.list.meshes.size(), 2u);
  const render::MeshInstance& ellipsoid = run.list.meshes[1];
  EXPECT_LT(ellipsoid.colour.a, 1.0f);
  const engine::BodyState& state = run.simulation.states()[0];
  Eigen::Affine3d expected = Eigen::Translation3d(state.position) * state.orientation;
  EXPECT_LT((ellipsoid.pose.cast<double>() - expected.matrix()).cwiseAbs().maxCoeff(), 1e-6);
}

// --- Trails and history -------------------------------------------------------------------

TEST(FrameBuilder, TrailKeepsTheLastSecondsOfABodyPoint) {
  const SceneSetup setup(brick_scene(
      R"({"show": {"angular_velocity": false, "angular_momentum": false, "overlay": false,
                   "trails": [{"body": "brick", "point": [0.2, 0.1, -0.3], "seconds": 1.0}]}})"));
  engine::Simulation simulation = setup.simulation();
  FrameBuilder builder = setup.builder();
  std::vector<Eigen::Vector3d> expected;
  for (int frame = 0; frame <= 75; ++frame) {
    frame_builder_advance_to(simulation, frame / 25.0);
    builder.observe(simulation);
    const engine::BodyState& state = simulation.states()[0];
    expected.push_back(state.position + engine::body_orientation(simulation.bodies()[0], state) *
                                            Eigen::Vector3d(0.2, 0.1, -0.3));
  }
  const render::DrawList list = builder.build(simulation);
  ASSERT_EQ(list.polylines.size(), 1u);
  // Frames at t = 2.0 .. 3.0 s: 26 points, the latest being the point now.
  const std::vector<Eigen::Vector3f>& points = list.polylines[0].points;
  ASSERT_EQ(points.size(), 26u);
  for (std::size_t k = 0; k < points.size(); ++k) {
    EXPECT_LT((to_double(points[k]) - expected[expected.size() - points.size() + k]).norm(), 1e-6);
  }
}

/// Exact equality of two draw lists, item by item.
void expect_same(const render::DrawList& a, const render::DrawList& b) {
  EXPECT_EQ(a.camera.eye, b.camera.eye);
  EXPECT_EQ(a.camera.target, b.camera.target);
  EXPECT_EQ(a.camera.near_plane, b.camera.near_plane);
  EXPECT_EQ(a.camera.far_plane, b.camera.far_plane);
  EXPECT_EQ(a.style.ground, b.style.ground);
  EXPECT_EQ(a.style.ground_height, b.style.ground_height);
  ASSERT_EQ(a.meshes.size(), b.meshes.size());
  for (std::size_t i = 0; i < a.meshes.size(); ++i) {
    // (Mesh ids differ: both builders upload to the one test renderer.)
    EXPECT_EQ(a.meshes[i].colour.a, b.meshes[i].colour.a);
    EXPECT_EQ(a.meshes[i].pose, b.meshes[i].pose);
  }
  ASSERT_EQ(a.arrows.size(), b.arrows.size());
  for (std::size_t i = 0; i < a.arrows.size(); ++i) {
    EXPECT_EQ(a.arrows[i].from, b.arrows[i].from);
    EXPECT_EQ(a.arrows[i].to, b.arrows[i].to);
  }
  ASSERT_EQ(a.polylines.size(), b.polylines.size());
  for (std::size_t i = 0; i < a.polylines.size(); ++i) {
    EXPECT_EQ(a.polylines[i].points, b.polylines[i].points);
  }
  ASSERT_EQ(a.labels.size(), b.labels.size());
  for (std::size_t i = 0; i < a.labels.size(); ++i) EXPECT_EQ(a.labels[i].text, b.labels[i].text);
  ASSERT_EQ(a.panels.size(), b.panels.size());
  for (std::size_t i = 0; i < a.panels.size(); ++i) {
    EXPECT_EQ(a.panels[i].lines, b.panels[i].lines);
    ASSERT_EQ(a.panels[i].plots.size(), b.panels[i].plots.size());
    for (std::size_t k = 0; k < a.panels[i].plots.size(); ++k) {
      EXPECT_EQ(a.panels[i].plots[k].values, b.panels[i].plots[k].values);
    }
  }
}

TEST(FrameBuilder, AFrameRangeEqualsTheSameFramesOfAFullRender) {
  const std::string render =
      R"({"camera": {"mode": "orbit", "orbit_period": 4},
          "show": {"herpolhode": true, "polhode": true, "trails": [{"point": [0.1, 0, 0]}]}})";
  const SceneSetup setup(brick_scene(render));

  // Full render: observe and build every frame.
  engine::Simulation full_run = setup.simulation();
  FrameBuilder full = setup.builder();
  std::vector<render::DrawList> full_frames;
  for (int frame = 0; frame < 10; ++frame) {
    frame_builder_advance_to(full_run, frame / 3.0);
    full.observe(full_run);
    full_frames.push_back(full.build(full_run));
  }

  // Frames 6..9 only: observe from the start, build from frame 6.
  engine::Simulation range_run = setup.simulation();
  FrameBuilder range = setup.builder();
  for (int frame = 0; frame < 10; ++frame) {
    frame_builder_advance_to(range_run, frame / 3.0);
    range.observe(range_run);
    if (frame >= 6)
      expect_same(range.build(range_run), full_frames[static_cast<std::size_t>(frame)]);
  }
  EXPECT_EQ(full_frames.back().polylines.size(), 3u);
  EXPECT_EQ(full_frames.back().panels.size(), 1u);
}

// --- Overlay and ground -------------------------------------------------------------------

TEST(FrameBuilder, OverlayOffMeansNoPanelsOrLabels) {
  const PoinsotRun run = run_brick(R"({"show": {"overlay": false, "herpolhode": true}})");
  EXPECT_TRUE(run.list.panels.empty());
  EXPECT_TRUE(run.list.labels.empty());
  EXPECT_FALSE(run.list.has_overlays());
}

TEST(FrameBuilder, OverlayShowsTitleIntegratorTimeAndDriftPlots) {
  const PoinsotRun run = run_brick(R"({})", "rk4", 1280, 720);
  ASSERT_EQ(run.list.panels.size(), 1u);
  const render::OverlayPanel& panel = run.list.panels[0];
  EXPECT_EQ(panel.title, "test");  // the scene's name: its file's stem
  ASSERT_GE(panel.lines.size(), 2u);
  EXPECT_THAT(panel.lines[0], HasSubstr("rk4"));
  EXPECT_THAT(panel.lines[0], HasSubstr("dt = 0.002 s"));
  EXPECT_THAT(panel.lines[1], HasSubstr("t = 6.000 s"));
  ASSERT_EQ(panel.plots.size(), 2u);
  // Relative drifts span decades: log axes.
  for (const render::Plot& plot : panel.plots) EXPECT_EQ(plot.axis, render::PlotAxis::kLog);
  // One value per observed frame, starting at zero drift; RK4 keeps the energy to ~1e-6 here.
  for (const render::Plot& plot : panel.plots) {
    ASSERT_EQ(plot.values.size(), 181u);
    EXPECT_EQ(plot.values.front(), 0.0f);
    for (float v : plot.values) EXPECT_LT(std::abs(v), 1e-4f);
  }
}

TEST(FrameBuilder, OverlayReportsABlowUpInRed) {
  // Explicit Euler on a fast, extreme-ratio spin grows the energy until the run stops.
  const std::string scene = R"({"duration": 50, "dt": 0.05, "integrator": "explicit-euler",
    "bodies": [{"name": "plate", "inertia": {"principal": [0.05, 1.0, 1.04]}, "mass": 1,
                "angular_velocity": [1, 20, 1], "angular_velocity_frame": "body"}]})";
  const SceneSetup setup(scene);
  engine::Simulation simulation = setup.simulation();
  FrameBuilder builder = setup.builder();
  while (!simulation.finished()) simulation.step();
  ASSERT_TRUE(simulation.blow_up().has_value());
  builder.observe(simulation);
  const render::DrawList list = builder.build(simulation);
  ASSERT_EQ(list.panels.size(), 1u);
  EXPECT_THAT(list.panels[0].lines.back(), HasSubstr("blew up at t = "));
  bool red_label = false;
  for (const render::Label& label : list.labels) {
    if (label.text.find("blew up") == std::string::npos) continue;
    red_label = label.colour.r > 0.8f && label.colour.g < 0.4f && label.colour.b < 0.4f;
    EXPECT_THAT(label.text, HasSubstr(simulation.blow_up()->reason));
  }
  EXPECT_TRUE(red_label);
}

TEST(FrameBuilder, GroundOffMeansNoGroundAndNoShadowPass) {
  const PoinsotRun run = run_brick(R"({"show": {"ground": false}})");
  EXPECT_FALSE(run.list.style.ground);
}

TEST(FrameBuilder, GroundLiesBelowAFallingBody) {
  const SceneSetup setup(
      R"({"duration": 1.5, "dt": 0.001, "gravity": [0, 0, -9.81], "bodies": [{"name": "t",
          "mesh": "../meshes/t_handle.obj", "density": 2700, "velocity": [0.5, 0, 4],
          "angular_velocity": [0.05, 10, 0.05], "angular_velocity_frame": "body"}],
          "render": {"show": {"ground": true}}})");
  const engine::TriangleMesh& geometry = *setup.scene.geometry[0];
  engine::Simulation simulation = setup.simulation();
  FrameBuilder builder = setup.builder();
  double lowest = 1e9;
  float ground = 0.0f;
  for (int frame = 0; frame <= 45; ++frame) {
    frame_builder_advance_to(simulation, frame / 30.0);
    builder.observe(simulation);
    const render::DrawList list = builder.build(simulation);
    EXPECT_TRUE(list.style.ground);
    EXPECT_TRUE(list.style.shadows);
    EXPECT_EQ(list.style.ground_normal, Eigen::Vector3f::UnitZ());
    ground = list.style.ground_height;
    const engine::BodyState& state = simulation.states()[0];
    const Eigen::Quaterniond turn = engine::body_orientation(simulation.bodies()[0], state);
    for (const Eigen::Vector3d& p : geometry.positions) {
      lowest = std::min(lowest, (state.position + turn * p).z());
    }
  }
  EXPECT_LT(ground, lowest);
  // ... and not far below it (the parabola's bottom is at the end: t = 1.5 s).
  EXPECT_GT(ground, lowest - 0.5);
}

// --- Camera -------------------------------------------------------------------------------

/// Directions spread over the sphere (Fibonacci lattice).
std::vector<Eigen::Vector3d> sphere_directions(int count) {
  std::vector<Eigen::Vector3d> out;
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < count; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / count;
    const double r = std::sqrt(1.0 - z * z);
    out.emplace_back(r * std::cos(golden * i), r * std::sin(golden * i), z);
  }
  return out;
}

/// Checks that every body's bounding ball stays inside the image at every frame.
void expect_bodies_in_view(const std::string& text) {
  const SceneSetup setup(text);
  std::vector<double> radii;
  for (std::size_t i = 0; i < setup.scene.bodies.size(); ++i) {
    double radius = 0.0;
    if (setup.scene.geometry[i]) {
      for (const Eigen::Vector3d& p : setup.scene.geometry[i]->positions) {
        radius = std::max(radius, p.norm());
      }
    } else {
      radius =
          0.5 *
          equivalent_box_size(setup.scene.bodies[i].mass, setup.scene.bodies[i].moments).norm();
    }
    radii.push_back(radius);
  }
  const std::vector<Eigen::Vector3d> directions = sphere_directions(200);
  engine::Simulation simulation = setup.simulation();
  FrameBuilder builder = setup.builder();
  const double fps = 10.0;
  for (int frame = 0; frame / fps <= setup.scene.settings.duration; ++frame) {
    frame_builder_advance_to(simulation, frame / fps);
    builder.observe(simulation);
    const render::Camera camera = builder.build(simulation).camera;
    for (std::size_t i = 0; i < radii.size(); ++i) {
      for (const Eigen::Vector3d& d : directions) {
        const Eigen::Vector3d world = simulation.states()[i].position + radii[i] * d;
        const Eigen::Vector3f pixel = render::project_to_pixels(
            camera, kFrameBuilderWidth, kFrameBuilderHeight, world.cast<float>());
        ASSERT_GT(pixel.z(), camera.near_plane) << "frame " << frame << " body " << i;
        EXPECT_GE(pixel.x(), 0.0f) << "frame " << frame << " body " << i;
        EXPECT_LE(pixel.x(), kFrameBuilderWidth) << "frame " << frame << " body " << i;
        EXPECT_GE(pixel.y(), 0.0f) << "frame " << frame << " body " << i;
        EXPECT_LE(pixel.y(), kFrameBuilderHeight) << "frame " << frame << " body " << i;
      }
    }
  }
}

const char* kFlyingBodies = R"({"duration": 3, "dt": 0.002, "gravity": [0, 0, -9.81],
  "bodies": [
    {"name": "t", "mesh": "../meshes/t_handle.obj", "density": 2700, "position": [0, 0, 1],
     "velocity": [1.5, 0.5, 12], "angular_velocity": [0.05, 10, 0.05],
     "angular_velocity_frame": "body"},
    {"name": "brick", "inertia": {"principal": [0.4, 0.9, 1.1]}, "mass": 2,
     "position": [-2, 1, 0], "velocity": [0, -1, 3], "angular_velocity": [1, 0, 2]}],
  "render": )";

TEST(FrameBuilder, AutoFramingKeepsEveryBodyInViewOverTheRun) {
  expect_bodies_in_view(std::string(kFlyingBodies) + R"({"camera": {"fov": 30}})" + "}");
}

TEST(FrameBuilder, OrbitingCameraKeepsEveryBodyInView) {
  expect_bodies_in_view(std::string(kFlyingBodies) +
                        R"({"camera": {"mode": "orbit", "orbit_period": 2, "elevation": 50}})" +
                        "}");
}

TEST(FrameBuilder, AutoFramingOfAPivotedTop) {
  expect_bodies_in_view(R"({"duration": 2, "dt": 0.0005, "integrator": "splitting",
      "gravity": [0, 0, -9.81], "bodies": [{"name": "top", "mesh": "../meshes/spinning_top.obj",
      "density": 1000, "orientation": [0.9887710779, 0.1494381325, 0, 0],
      "pivot": [0, 0, -0.018958], "angular_velocity": [0, 0, 120.0],
      "angular_velocity_frame": "body"}], "render": {"show": {"ground": true}}})");
}

TEST(FrameBuilder, CameraModesPlaceTheEye) {
  // Fixed with an explicit eye and target: exactly those.
  {
    const SceneSetup setup(
        brick_scene(R"({"camera": {"eye": [3, -4, 2], "target": [0, 0, 0.5]}})"));
    engine::Simulation simulation = setup.simulation();
    FrameBuilder builder = setup.builder();
    builder.observe(simulation);
    const render::Camera camera = builder.build(simulation).camera;
    EXPECT_EQ(camera.eye, Eigen::Vector3f(3, -4, 2));
    EXPECT_EQ(camera.target, Eigen::Vector3f(0, 0, 0.5));
  }
  // Orbit: a quarter period turns the eye a quarter turn about z around the target.
  {
    const SceneSetup setup(brick_scene(
        R"({"camera": {"mode": "orbit", "eye": [2, 0, 1], "target": [0, 0, 0], "orbit_period": 4}})"));
    engine::Simulation simulation = setup.simulation();
    FrameBuilder builder = setup.builder();
    frame_builder_advance_to(simulation, 1.0);
    builder.observe(simulation);
    const render::Camera camera = builder.build(simulation).camera;
    EXPECT_LT((camera.eye - Eigen::Vector3f(0, 2, 1)).norm(), 1e-5f);
  }
  // Follow: the target is the body's centre of mass, the eye at a fixed offset from it.
  {
    const SceneSetup setup(
        R"({"duration": 2, "dt": 0.01, "bodies": [{"name": "b", "inertia": {"principal": [1, 2, 3]},
            "mass": 1, "velocity": [1, 2, 0]}], "render": {"camera": {"mode": "follow",
            "follow": "b", "distance": 5}}})");
    engine::Simulation simulation = setup.simulation();
    FrameBuilder builder = setup.builder();
    builder.observe(simulation);
    const render::Camera first = builder.build(simulation).camera;
    frame_builder_advance_to(simulation, 1.5);
    builder.observe(simulation);
    const render::Camera later = builder.build(simulation).camera;
    EXPECT_LT((later.target - simulation.states()[0].position.cast<float>()).norm(), 1e-5f);
    EXPECT_LT(((later.eye - later.target) - (first.eye - first.target)).norm(), 1e-5f);
    EXPECT_NEAR((first.eye - first.target).norm(), 5.0f, 1e-5f);
  }
}

}  // namespace
}  // namespace tumble::app
