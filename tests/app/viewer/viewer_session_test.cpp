#include "app/viewer/viewer_session.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/scene/mesh_inspection.hpp"
#include "app/viewer/viewer_initial_state.hpp"
#include "base/errors.hpp"
#include "engine/simulation/simulation.hpp"
#include "render/renderer.hpp"
#include "support/command_test.hpp"
#include "support/scene_builder.hpp"

namespace tumble::app::viewer {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

/// Generous stepping budget, so that a loaded machine never cuts a call short.
constexpr std::chrono::steady_clock::duration kNoBudget = std::chrono::seconds(60);

std::filesystem::path asset(const std::string& relative) {
  return std::filesystem::path(TUMBLE_SOURCE_DIR) / "assets" / relative;
}

/// A free brick (moments 1 : 2 : 3) spinning near its intermediate axis; dt = 3 ms divides
/// neither 0.1 s nor 1/60 s, so rounding to whole steps shows.
nlohmann::json brick_scene(double duration = 5.0, double dt = 0.003) {
  return testing::SceneBuilder()
      .duration(duration)
      .dt(dt)
      .body(testing::BodyBuilder("brick").angular_velocity({0.1, 2.0, 0.1}))
      .json();
}

/// The brick with a constant torque: not torque-free, so the exact integrator refuses it.
nlohmann::json pushed_scene() {
  nlohmann::json scene = brick_scene();
  scene["bodies"][0]["torque"] = {0.0, 0.0, 0.1};
  return scene;
}

void expect_same_state(const engine::BodyState& a, const engine::BodyState& b) {
  EXPECT_EQ(a.position, b.position);
  EXPECT_EQ(a.velocity, b.velocity);
  EXPECT_EQ(a.orientation.coeffs(), b.orientation.coeffs());
  EXPECT_EQ(a.angular_momentum, b.angular_momentum);
}

class ViewerSession : public testing::CommandTest {
 protected:
  static void SetUpTestSuite() { renderer_ = std::make_unique<render::Renderer>(options()); }
  static void TearDownTestSuite() { renderer_.reset(); }
  static render::RendererOptions options() {
    render::RendererOptions o;
    o.width = 320;
    o.height = 240;
    return o;
  }

  /// A session with `scene` (written to the test's folder) open.
  std::unique_ptr<Session> open(const nlohmann::json& scene,
                                const std::string& name = "scene.json") {
    auto session = std::make_unique<Session>(*renderer_);
    const auto error = session->open(write_scene(scene, name));
    EXPECT_FALSE(error) << *error;
    return session;
  }

  static std::unique_ptr<render::Renderer> renderer_;
};
std::unique_ptr<render::Renderer> ViewerSession::renderer_;

// --- Opening -------------------------------------------------------------------------------------

TEST_F(ViewerSession, OpensASceneAtTimeZeroWithItsIntegrator) {
  auto session = open(brick_scene());
  EXPECT_FALSE(session->empty());
  EXPECT_EQ(session->run_count(), 1u);
  EXPECT_EQ(session->integrator(), "rk4");
  EXPECT_EQ(session->dt(), 0.003);
  EXPECT_EQ(session->time(), 0.0);
  EXPECT_FALSE(session->paused());
  ASSERT_EQ(session->simulation().states().size(), 1u);
  expect_same_state(session->simulation().states()[0], session->initial_state(0));
  // Initial w is the scene's (world frame by default): L = diag(1, 2, 3) w.
  EXPECT_NEAR((session->initial_state(0).angular_momentum - Eigen::Vector3d(0.1, 4.0, 0.3)).norm(),
              0.0, 1e-15);
  EXPECT_EQ(session->history().time.size(), 1u);
}

TEST_F(ViewerSession, OpensWithTheCommandLinesIntegratorAndStep) {
  Session session(*renderer_);
  const auto file = write_scene(brick_scene(), "scene.json");
  EXPECT_FALSE(session.open(file, {"splitting", 0.002}));
  EXPECT_EQ(session.run_count(), 1u);
  EXPECT_EQ(session.integrator(), "splitting");
  EXPECT_EQ(session.dt(), 0.002);
  // Only the step: the scene's integrator.
  EXPECT_FALSE(session.open(file, {std::nullopt, 0.005}));
  EXPECT_EQ(session.integrator(), "rk4");
  EXPECT_EQ(session.dt(), 0.005);
  // A bad choice is refused naming the option, and what was open stays.
  EXPECT_THAT(session.open(file, {"leapfrog", std::nullopt}).value_or(""),
              HasSubstr("--integrator: unknown integrator \"leapfrog\""));
  EXPECT_THAT(session.open(file, {std::nullopt, -1.0}).value_or(""),
              HasSubstr("--dt: expected a positive finite number"));
  EXPECT_EQ(session.integrator(), "rk4");
  EXPECT_EQ(session.dt(), 0.005);
}

TEST_F(ViewerSession, EmptySessionIgnoresTheClock) {
  Session session(*renderer_);
  EXPECT_TRUE(session.empty());
  session.advance(1.0, kNoBudget);
  session.step();
  session.reset();
  EXPECT_EQ(session.time(), 0.0);
  EXPECT_FALSE(session.finished());
  EXPECT_THAT(session.set_integrator("rk4", 0.01, false).value_or(""),
              HasSubstr("nothing is open"));
}

// --- Clock ---------------------------------------------------------------------------------------

// Regression: the clock once restarted from the simulated time each call, so overshoots added
// up (335 steps for ten calls against 333 for one).
TEST_F(ViewerSession, AdvanceFollowsTheWallClockNotTheFrameRate) {
  // One call of 1 s: the steps whose end is at most half a step past 1 s.
  auto once = open(brick_scene());
  once->advance(1.0, kNoBudget);
  EXPECT_NEAR(once->time(), 1.0, 0.003);
  EXPECT_EQ(once->simulation().steps(), 333u);  // 333 x 3 ms = 0.999 s; 334 would end at 1.002

  // Ten calls of 0.1 s: the same simulated time, the same state.
  auto tenths = open(brick_scene(), "tenths.json");
  for (int i = 0; i < 10; ++i) tenths->advance(0.1, kNoBudget);
  EXPECT_NEAR(tenths->time(), 1.0, 0.003);
  EXPECT_EQ(tenths->simulation().steps(), once->simulation().steps());
}

// Regression: the clock once restarted from max(target, now) every call, and a step may end
// half a step past the target, so each overshoot was added: 10 s of wall time at 60 frames/s
// with dt = 10 ms simulated 12 s.
TEST_F(ViewerSession, AdvanceAtSixtyFramesPerSecondKeepsRealTime) {
  nlohmann::json scene = brick_scene(30.0, 0.01);
  auto session = open(scene);
  for (int i = 0; i < 600; ++i) session->advance(1.0 / 60.0, kNoBudget);
  EXPECT_NEAR(session->time(), 10.0, 0.01);
}

TEST_F(ViewerSession, PausedAdvanceDoesNothing) {
  auto session = open(brick_scene());
  session->set_paused(true);
  session->advance(1.0, kNoBudget);
  EXPECT_EQ(session->time(), 0.0);
  EXPECT_EQ(session->simulation().steps(), 0u);
  expect_same_state(session->simulation().states()[0], session->initial_state(0));
  // Unpaused, the time spent paused is not made up for.
  session->set_paused(false);
  session->advance(0.3, kNoBudget);
  EXPECT_NEAR(session->time(), 0.3, 0.0015 + 1e-12);
}

TEST_F(ViewerSession, TimeScaleMultipliesWallTimeAndIsClamped) {
  auto session = open(brick_scene());
  EXPECT_EQ(session->time_scale(), 1.0);
  session->set_time_scale(4.0);
  session->advance(0.25, kNoBudget);
  EXPECT_NEAR(session->time(), 1.0, 0.0015 + 1e-12);
  session->set_time_scale(0.25);
  session->advance(1.0, kNoBudget);
  EXPECT_NEAR(session->time(), 1.25, 0.0015 + 1e-12);

  session->set_time_scale(1000.0);
  EXPECT_EQ(session->time_scale(), 64.0);
  session->set_time_scale(1e-6);
  EXPECT_EQ(session->time_scale(), 1.0 / 64.0);
  session->set_time_scale(std::numeric_limits<double>::quiet_NaN());
  EXPECT_EQ(session->time_scale(), 1.0 / 64.0);
  session->set_time_scale(std::numeric_limits<double>::infinity());
  EXPECT_EQ(session->time_scale(), 1.0 / 64.0);
}

TEST_F(ViewerSession, StepTakesExactlyOneDtAndPauses) {
  auto session = open(brick_scene());
  EXPECT_FALSE(session->paused());
  session->step();
  EXPECT_TRUE(session->paused());
  EXPECT_EQ(session->simulation().steps(), 1u);
  EXPECT_EQ(session->time(), 0.003);
  // The same as an engine run of one step.
  const CompiledScene compiled = compile_scene(session->scene());
  engine::Simulation reference(compiled.bodies, compiled.initial, compiled.settings);
  reference.step();
  expect_same_state(session->simulation().states()[0], reference.states()[0]);
  session->step();
  EXPECT_EQ(session->simulation().steps(), 2u);
  EXPECT_EQ(session->time(), 0.006);
  // Unpausing after steps carries on from there, in wall time.
  session->set_paused(false);
  session->advance(0.03, kNoBudget);
  EXPECT_NEAR(session->time(), 0.036, 0.0015 + 1e-12);
}

TEST_F(ViewerSession, ResetReturnsToTheInitialStateBitForBit) {
  auto session = open(brick_scene());
  session->advance(0.5, kNoBudget);
  const engine::BodyState at_half = session->simulation().states()[0];
  ASSERT_GT(session->time(), 0.4);
  const std::size_t generation = session->generation();
  session->reset();
  EXPECT_EQ(session->time(), 0.0);
  EXPECT_GT(session->generation(), generation);
  expect_same_state(session->simulation().states()[0], session->initial_state(0));
  EXPECT_EQ(session->history().time.size(), 1u);
  // Deterministic: the same wall time gives the same state again.
  session->advance(0.5, kNoBudget);
  expect_same_state(session->simulation().states()[0], at_half);
}

TEST_F(ViewerSession, PausesAtTheEndOfTheScene) {
  auto session = open(brick_scene(0.5, 0.003));
  session->advance(2.0, kNoBudget);
  EXPECT_TRUE(session->finished());
  EXPECT_TRUE(session->paused());
  EXPECT_EQ(session->time(), 0.5);
  const std::size_t steps = session->simulation().steps();
  EXPECT_EQ(steps, 167u);  // 166 steps of 3 ms and a last one of 2 ms
  session->set_paused(false);
  session->advance(1.0, kNoBudget);
  EXPECT_EQ(session->simulation().steps(), steps);
  session->step();
  EXPECT_EQ(session->simulation().steps(), steps);
}

TEST_F(ViewerSession, SteppingDebtBeyondAQuarterSecondIsDropped) {
  // With no budget a call stops after its first 32 steps; the clock keeps the rest as debt, but
  // never more than 0.25 s of wall time (x time scale) of it, so a stall is not raced after.
  auto session = open(brick_scene(30.0, 0.003));
  session->advance(2.0, std::chrono::steady_clock::duration::zero());
  EXPECT_EQ(session->simulation().steps(), 32u);
  session->advance(0.0, kNoBudget);
  EXPECT_NEAR(session->time(), 32 * 0.003 + 0.25, 0.0015 + 1e-12);
  // Nothing left to catch up on.
  const std::size_t steps = session->simulation().steps();
  session->advance(0.0, kNoBudget);
  EXPECT_EQ(session->simulation().steps(), steps);
}

TEST_F(ViewerSession, RealTimeFactorIsSimulatedOverWallSecondsPerSecond) {
  // dt = 1/256 s: every call's 0.5 simulated seconds are whole steps (no rounding to steps).
  auto session = open(brick_scene(30.0, 1.0 / 256.0));
  EXPECT_EQ(session->real_time_factor(), 0.0);
  session->set_time_scale(2.0);
  for (int i = 0; i < 3; ++i) session->advance(0.25, kNoBudget);
  EXPECT_EQ(session->real_time_factor(), 0.0);  // less than a second of wall time so far
  session->advance(0.25, kNoBudget);
  // 1 s of wall time at scale 2: 2 simulated seconds.
  EXPECT_EQ(session->simulation().steps(), 512u);
  EXPECT_EQ(session->real_time_factor(), 2.0);
  EXPECT_EQ(session->real_time_factor(), session->time());
  // Paused, the simulated time stands still while the wall clock runs.
  session->set_paused(true);
  session->advance(1.0, kNoBudget);
  EXPECT_EQ(session->real_time_factor(), 0.0);
}

// --- Runs ----------------------------------------------------------------------------------------

TEST_F(ViewerSession, SetIntegratorRestartsWithTheNewOne) {
  auto session = open(brick_scene());
  session->advance(0.2, kNoBudget);
  EXPECT_FALSE(session->set_integrator("midpoint", 0.002, false));
  EXPECT_EQ(session->run_count(), 1u);
  EXPECT_EQ(session->integrator(), "midpoint");
  EXPECT_EQ(session->dt(), 0.002);
  EXPECT_EQ(session->time(), 0.0);
  EXPECT_EQ(session->simulation().settings().integrator, engine::IntegratorKind::kMidpoint);
  EXPECT_EQ(session->simulation().settings().dt, 0.002);
  session->step();
  EXPECT_EQ(session->time(), 0.002);
}

TEST_F(ViewerSession, SetIntegratorRefusalsChangeNothing) {
  auto session = open(pushed_scene());
  session->advance(0.2, kNoBudget);
  const double time = session->time();
  const std::size_t generation = session->generation();
  const auto unchanged = [&](const std::string& what) {
    EXPECT_EQ(session->run_count(), 1u) << what;
    EXPECT_EQ(session->integrator(), "rk4") << what;
    EXPECT_EQ(session->dt(), 0.003) << what;
    EXPECT_EQ(session->time(), time) << what;
    EXPECT_EQ(session->generation(), generation) << what;
  };

  EXPECT_THAT(session->set_integrator("nope", 0.01, false).value_or(""),
              HasSubstr("integrator: unknown \"nope\" (expected one of"));
  unchanged("unknown");
  for (const double dt : {0.0, -0.01, std::numeric_limits<double>::quiet_NaN(),
                          std::numeric_limits<double>::infinity()}) {
    EXPECT_THAT(session->set_integrator("rk4", dt, false).value_or(""),
                HasSubstr("dt: expected a positive number of seconds"))
        << dt;
    unchanged("dt");
  }
  EXPECT_THAT(session->set_integrator("rk4", 6.0, false).value_or(""),
              HasSubstr("dt: expected a step no longer than the duration"));
  unchanged("long dt");
  EXPECT_THAT(session->set_integrator("exact", 0.01, false).value_or(""),
              HasSubstr("body 'brick': the exact integrator needs a torque-free body"));
  unchanged("exact");
  EXPECT_THAT(session->set_integrator("exact", 0.01, true).value_or(""),
              HasSubstr("the exact integrator needs a torque-free body"));
  unchanged("exact beside");
}

TEST_F(ViewerSession, BesideAddsTranslucentRunsAndALegend) {
  auto session = open(brick_scene());
  const render::Camera camera;
  const render::DrawList alone = session->frame(camera);
  ASSERT_EQ(alone.meshes.size(), 1u);
  for (const auto& panel : alone.panels) EXPECT_NE(panel.title, "runs");

  session->advance(0.2, kNoBudget);
  EXPECT_FALSE(session->set_integrator("explicit-euler", 0.01, true));
  EXPECT_EQ(session->run_count(), 2u);
  EXPECT_EQ(session->integrator(0), "rk4");
  EXPECT_EQ(session->integrator(1), "explicit-euler");
  EXPECT_EQ(session->dt(1), 0.01);
  EXPECT_EQ(session->time(), 0.0);  // both restart together
  EXPECT_EQ(session->simulation(1).time(), 0.0);

  // Every run follows the clock with its own dt.
  session->advance(0.1, kNoBudget);
  EXPECT_NEAR(session->simulation(0).time(), 0.1, 0.0015 + 1e-12);
  EXPECT_NEAR(session->simulation(1).time(), 0.1, 0.005 + 1e-12);

  const render::DrawList both = session->frame(camera);
  ASSERT_EQ(both.meshes.size(), 2u);
  EXPECT_EQ(both.meshes[0].colour.a, alone.meshes[0].colour.a);
  const RunColour green = beside_colour(1);
  EXPECT_STREQ(green.name, "green");
  EXPECT_EQ(both.meshes[1].colour.r, green.colour.r);
  EXPECT_EQ(both.meshes[1].colour.g, green.colour.g);
  EXPECT_LT(both.meshes[1].colour.a, 1.0f);
  const render::OverlayPanel* legend = nullptr;
  for (const auto& panel : both.panels) {
    if (panel.title == "runs") legend = &panel;
  }
  ASSERT_NE(legend, nullptr);
  ASSERT_EQ(legend->lines.size(), 2u);
  EXPECT_EQ(legend->lines[0], "solid: rk4, dt = 0.003 s");
  EXPECT_EQ(legend->lines[1], "green: explicit-euler, dt = 0.01 s");

  // Up to kMaxRuns, then refused without change.
  EXPECT_FALSE(session->set_integrator("midpoint", 0.005, true));
  EXPECT_FALSE(session->set_integrator("splitting", 0.02, true));
  EXPECT_EQ(session->run_count(), kMaxRuns);
  EXPECT_THAT(session->set_integrator("rk4", 0.001, true).value_or(""),
              HasSubstr("at most 4 runs side by side"));
  EXPECT_EQ(session->run_count(), kMaxRuns);
  EXPECT_EQ(session->integrator(3), "splitting");
  const render::DrawList four = session->frame(camera);
  EXPECT_EQ(four.meshes.size(), 4u);
  EXPECT_EQ(four.meshes[3].colour.b, beside_colour(3).colour.b);
  // Switching the bodies off hides every run's, and the overlay names the first run's
  // integrator and dt.
  session->show().bodies = false;
  const render::DrawList hidden = session->frame(camera);
  EXPECT_TRUE(hidden.meshes.empty());
  const auto overlay = std::find_if(hidden.panels.begin(), hidden.panels.end(),
                                    [](const auto& panel) { return panel.title != "runs"; });
  ASSERT_NE(overlay, hidden.panels.end());
  EXPECT_THAT(overlay->lines, ::testing::Contains("integrator rk4, dt = 0.003 s"));
  session->show().bodies = true;

  // Without `beside`, the runs are replaced by one.
  session->advance(0.1, kNoBudget);
  const double time = session->time();
  session->remove_beside_runs();
  EXPECT_EQ(session->run_count(), 1u);
  EXPECT_EQ(session->integrator(), "rk4");
  EXPECT_EQ(session->time(), time);  // restarts nothing
  const render::DrawList again = session->frame(camera);
  EXPECT_EQ(again.meshes.size(), 1u);
  for (const auto& panel : again.panels) EXPECT_NE(panel.title, "runs");
}

// Regression: the legend was once placed from the scene's video height (720 by default), off
// screen in a 320x240 window.
TEST_F(ViewerSession, LegendIsInsideTheWindow) {
  auto session = open(brick_scene());
  ASSERT_FALSE(session->set_integrator("explicit-euler", 0.01, true));
  const render::DrawList list = session->frame(render::Camera{});
  bool found = false;
  for (const auto& panel : list.panels) {
    if (panel.title != "runs") continue;
    found = true;
    EXPECT_GE(panel.position_px.y(), 0.0f);
    EXPECT_LT(panel.position_px.y(), static_cast<float>(renderer_->height()));
  }
  EXPECT_TRUE(found);
}

TEST_F(ViewerSession, ResetRestartsEveryRun) {
  auto session = open(brick_scene());
  ASSERT_FALSE(session->set_integrator("semi-implicit-euler", 0.004, true));
  session->advance(0.3, kNoBudget);
  ASSERT_GT(session->simulation(1).time(), 0.0);
  session->reset();
  EXPECT_EQ(session->run_count(), 2u);
  EXPECT_EQ(session->simulation(0).time(), 0.0);
  EXPECT_EQ(session->simulation(1).time(), 0.0);
  expect_same_state(session->simulation(1).states()[0], session->initial_state(0));
}

// --- Opening files -------------------------------------------------------------------------------

TEST_F(ViewerSession, FailedOpensNameTheFileAndKeepTheScene) {
  auto session = open(brick_scene());
  session->advance(0.3, kNoBudget);
  const double time = session->time();
  const std::filesystem::path file = session->scene().file;

  const auto kept = [&](const std::string& what) {
    EXPECT_EQ(session->scene().file, file) << what;
    EXPECT_EQ(session->run_count(), 1u) << what;
    EXPECT_EQ(session->integrator(), "rk4") << what;
    EXPECT_EQ(session->time(), time) << what;
  };

  const std::string missing_scene = path("missing.json");
  EXPECT_THAT(session->open(missing_scene).value_or(""), HasSubstr(missing_scene));
  kept("missing scene");

  const std::string broken = path("broken.json");
  std::ofstream(broken) << "{ \"duration\": 1, ";
  EXPECT_THAT(session->open(broken).value_or(""), StartsWith(broken));
  kept("broken scene");

  nlohmann::json invalid = brick_scene();
  invalid["bodies"][0]["angular_velocity"] = {1, 2};
  const std::string invalid_file = write_scene(invalid, "invalid.json");
  EXPECT_THAT(session->open(invalid_file).value_or(""),
              HasSubstr(invalid_file + ": bodies[0].angular_velocity"));
  kept("invalid scene");

  const std::string missing_mesh = path("missing.obj");
  EXPECT_THAT(session->open(missing_mesh).value_or(""), HasSubstr(missing_mesh + ": no such file"));
  kept("missing mesh");

  const std::string garbage = path("garbage.stl");
  std::ofstream(garbage) << "this is not a mesh\n";
  EXPECT_THAT(session->open(garbage).value_or(""), HasSubstr(garbage));
  kept("broken mesh");
}

// Regression: a scene whose integrator refuses a body once gave a message without the file
// and restarted the open scene from t = 0.
TEST_F(ViewerSession, SceneWhoseIntegratorRefusesItKeepsTheOldRunGoing) {
  auto session = open(brick_scene());
  session->advance(0.3, kNoBudget);
  const double time = session->time();
  const std::size_t generation = session->generation();
  nlohmann::json refused = pushed_scene();
  refused["integrator"] = "exact";
  const std::string file = write_scene(refused, "refused.json");
  const std::string error = session->open(file).value_or("");
  EXPECT_THAT(error, HasSubstr("the exact integrator needs a torque-free body"));
  EXPECT_THAT(error, HasSubstr(file));
  EXPECT_EQ(session->integrator(), "rk4");
  EXPECT_EQ(session->time(), time);
  EXPECT_EQ(session->generation(), generation);
}

TEST_F(ViewerSession, OpeningAMeshSpinsItAboutItsIntermediateAxis) {
  const std::filesystem::path mesh = asset("meshes/t_handle.obj");
  Session session(*renderer_);
  ASSERT_FALSE(session.open(mesh));
  ASSERT_EQ(session.compiled().bodies.size(), 1u);
  EXPECT_EQ(session.integrator(), "rk4");
  EXPECT_EQ(session.dt(), 1e-3);
  EXPECT_EQ(session.scene().duration, 60.0);
  EXPECT_EQ(session.compiled().bodies[0].name, "t_handle");

  // Mass properties as `tumble inspect` finds them at 1000 kg/m^3.
  engine::MassOptions mass;
  mass.density = 1000.0;
  const engine::MeshReport report = inspect_file(mesh, mass);
  const engine::BodyModel& body = session.compiled().bodies[0];
  EXPECT_NEAR(body.mass, report.mass_properties.mass, 1e-12 * report.mass_properties.mass);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(body.moments[k], report.principal.moments[k], 1e-12 * report.principal.moments[2]);
  }
  ASSERT_LT(body.moments[0], body.moments[1]);
  ASSERT_LT(body.moments[1], body.moments[2]);

  // w in the principal frame = kMeshSpinRate (p, 1, p), p = kPresetPerturbation.
  const engine::BodyState& state = session.initial_state(0);
  const Eigen::Vector3d local = state.orientation.conjugate() * state.angular_momentum;
  const Eigen::Vector3d w = local.cwiseQuotient(body.moments);
  EXPECT_NEAR(w[0], kMeshSpinRate * kPresetPerturbation, 1e-12);
  EXPECT_NEAR(w[1], kMeshSpinRate, 1e-12);
  EXPECT_NEAR(w[2], kMeshSpinRate * kPresetPerturbation, 1e-12);
  EXPECT_EQ(state.position, Eigen::Vector3d::Zero());
}

TEST_F(ViewerSession, InspectorShowsTheInspectReport) {
  const std::filesystem::path mesh = asset("meshes/coin.obj");
  Session session(*renderer_);
  ASSERT_FALSE(session.open(mesh));
  engine::MassOptions mass;
  mass.density = 1000.0;
  const std::string expected = format_report(inspect_file(mesh, mass));
  const std::string text = session.inspector_text(0);
  // The first line names the source; every line after it (the numbers) is the same.
  ASSERT_NE(expected.find('\n'), std::string::npos);
  ASSERT_NE(text.find('\n'), std::string::npos);
  EXPECT_EQ(text.substr(text.find('\n')), expected.substr(expected.find('\n')));
  EXPECT_THAT(text, HasSubstr("principal moments"));
  EXPECT_EQ(session.inspector_text(1), "");

  // Given inertia: mass and moments.
  auto given = open(brick_scene());
  const std::string brick = given->inspector_text(0);
  EXPECT_THAT(brick, HasSubstr("brick: inertia given in the scene"));
  EXPECT_THAT(brick, HasSubstr("mass              2 kg"));
  EXPECT_THAT(brick, HasSubstr("principal moments 1, 2, 3 kg m^2"));
  EXPECT_TRUE(given->inspector_warnings(0).empty());
}

// --- Initial state -------------------------------------------------------------------------------

TEST_F(ViewerSession, SetInitialStateRestartsFromIt) {
  auto session = open(brick_scene());
  ASSERT_FALSE(session->set_integrator("midpoint", 0.003, true));
  session->advance(0.4, kNoBudget);
  const std::size_t generation = session->generation();
  const engine::BodyModel& body = session->compiled().bodies[0];
  engine::BodyState state = session->initial_state(0);
  set_initial_omega(body, state, Eigen::Vector3d(3.0, 0.0, 0.5), VectorFrame::kWorld);
  set_orientation_ypr_deg(body, state, Eigen::Vector3d(10, 20, 30));
  session->set_initial_state(0, state);

  EXPECT_GT(session->generation(), generation);
  EXPECT_EQ(session->time(), 0.0);
  EXPECT_EQ(session->run_count(), 2u);
  expect_same_state(session->initial_state(0), state);
  expect_same_state(session->simulation(0).states()[0], state);
  expect_same_state(session->simulation(1).states()[0], state);
  // Body-frame w of the new state is what the plots start from.
  const Eigen::Vector3d w = initial_omega(body, state, VectorFrame::kBody);
  ASSERT_EQ(session->history().omega[0].size(), 1u);
  for (int a = 0; a < 3; ++a) EXPECT_EQ(session->history().omega[a][0], static_cast<float>(w[a]));
  // Reset returns to the new state.
  session->advance(0.2, kNoBudget);
  session->reset();
  expect_same_state(session->simulation().states()[0], state);
}

// --- History -------------------------------------------------------------------------------------

TEST_F(ViewerSession, HistoryGrowsWithStepsAndIsBounded) {
  auto session = open(brick_scene(30.0, 0.003));
  const History& history = session->history();
  ASSERT_EQ(history.time.size(), 1u);
  EXPECT_EQ(history.time[0], 0.0f);
  EXPECT_EQ(history.energy_drift[0], 0.0f);
  EXPECT_EQ(history.momentum_drift[0], 0.0f);
  // w_body at t = 0 (body = principal frame here): (0.1, 2, 0.1).
  EXPECT_NEAR(history.omega[1][0], 2.0f, 1e-6f);

  // One sample per call that stepped, none for a call that did not.
  session->advance(0.03, kNoBudget);
  session->advance(0.0001, kNoBudget);
  ASSERT_EQ(history.time.size(), 2u);
  EXPECT_EQ(history.time[1], static_cast<float>(session->time()));
  EXPECT_EQ(history.omega[0].size(), 2u);

  // Many samples: the oldest are dropped, never more than kHistoryLength plus a quarter (the
  // chunk dropped at once), and the newest sample is the current time.
  std::size_t most = 0;
  for (int i = 0; i < 2000; ++i) {
    session->step();
    most = std::max(most, history.time.size());
  }
  EXPECT_GE(history.time.size(), Session::kHistoryLength);
  EXPECT_LE(most, Session::kHistoryLength + Session::kHistoryLength / 4);
  EXPECT_EQ(history.energy_drift.size(), history.time.size());
  EXPECT_EQ(history.momentum_drift.size(), history.time.size());
  EXPECT_EQ(history.omega[2].size(), history.time.size());
  EXPECT_EQ(history.time.back(), static_cast<float>(session->time()));
  // Samples are consecutive steps: oldest = newest - (size - 1) dt.
  EXPECT_NEAR(history.time.front(),
              session->time() - 0.003 * static_cast<double>(history.time.size() - 1), 1e-4);
  // Torque-free rk4 at dt = 3 ms: |L| drift small but recorded against |L0|.
  EXPECT_LT(std::abs(history.momentum_drift.back()), 1e-6f);
}

TEST_F(ViewerSession, PlottedBodyChoosesWhoseOmegaIsRecorded) {
  nlohmann::json scene = brick_scene();
  scene["bodies"].push_back({{"name", "rod"},
                             {"inertia", {{"principal", {0.5, 4, 4}}}},
                             {"mass", 1.0},
                             {"angular_velocity", {7.0, 0.0, -1.5}}});
  auto session = open(scene);
  session->advance(0.1, kNoBudget);
  ASSERT_EQ(session->history().time.size(), 2u);
  EXPECT_NEAR(session->history().omega[0][0], 0.1f, 1e-7f);
  session->set_plotted_body(1);
  EXPECT_EQ(session->plotted_body(), 1u);
  // Plots start again from now, for the rod: w_body of a torque-free axisymmetric rod keeps
  // its axial component, 7 rad/s.
  ASSERT_EQ(session->history().time.size(), 1u);
  EXPECT_EQ(session->history().time[0], static_cast<float>(session->time()));
  EXPECT_NEAR(session->history().omega[0][0], 7.0f, 1e-5f);
  session->set_plotted_body(2);  // no such body: ignored
  EXPECT_EQ(session->plotted_body(), 1u);
  EXPECT_EQ(session->history().time.size(), 1u);
}

// --- Drawing -------------------------------------------------------------------------------------

TEST_F(ViewerSession, EllipsoidToggleMidRunKeepsTheSimulatedTime) {
  auto session = open(brick_scene());
  session->advance(0.5, kNoBudget);
  session->set_paused(true);
  const double time = session->time();
  const engine::BodyState state = session->simulation().states()[0];
  const render::Camera camera;
  const std::size_t meshes = session->frame(camera).meshes.size();

  session->show().inertia_ellipsoid = true;
  const render::DrawList with = session->frame(camera);
  EXPECT_EQ(with.meshes.size(), meshes + 1);
  EXPECT_EQ(session->time(), time);
  expect_same_state(session->simulation().states()[0], state);
  EXPECT_TRUE(session->paused());

  session->show().inertia_ellipsoid = false;
  EXPECT_EQ(session->frame(camera).meshes.size(), meshes);
  EXPECT_EQ(session->time(), time);
  expect_same_state(session->simulation().states()[0], state);
}

// Regression: switching the ellipsoid on once rebuilt the runs, which cleared the live plots,
// bumped generation() as if the runs had restarted, and left the drawn herpolhode and polhode
// with two points (the replay observed the runs only at its end).
TEST_F(ViewerSession, EllipsoidToggleKeepsThePlotsAndTheDrawnPaths) {
  auto session = open(brick_scene());
  session->show().herpolhode = true;
  session->show().polhode = true;
  session->show_trails() = false;
  for (int i = 0; i < 10; ++i) session->advance(0.05, kNoBudget);
  const std::vector<float> times = session->history().time;
  ASSERT_EQ(times.size(), 11u);
  const std::size_t generation = session->generation();
  const auto path_points = [&] {
    std::vector<std::size_t> points;
    for (const render::Polyline& line : session->frame(render::Camera{}).polylines) {
      points.push_back(line.points.size());
    }
    return points;
  };
  const std::vector<std::size_t> before = path_points();
  ASSERT_EQ(before.size(), 2u);  // herpolhode and polhode
  EXPECT_GE(before[0], 11u);
  session->show().inertia_ellipsoid = true;
  EXPECT_EQ(path_points(), before);
  EXPECT_EQ(session->history().time, times);
  EXPECT_EQ(session->generation(), generation);
}

TEST_F(ViewerSession, TrailsToggle) {
  auto session = open(brick_scene());
  session->advance(0.5, kNoBudget);
  const render::Camera camera;
  session->show_trails() = false;
  const std::size_t without = session->frame(camera).polylines.size();
  session->show_trails() = true;
  EXPECT_EQ(session->frame(camera).polylines.size(), without + 1);
}

}  // namespace
}  // namespace tumble::app::viewer
