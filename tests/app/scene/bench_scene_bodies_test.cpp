// The bodies written out in tests/support/bench_scene_bodies.hpp (for the engine tests of
// dopri's tolerance on the bench's scenes) are the ones the scene files compile to.
#include "support/bench_scene_bodies.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <variant>

#include "app/scene/scene.hpp"

namespace tumble::app {
namespace {

void expect_near_vector(const Eigen::Vector3d& actual, const Eigen::Vector3d& expected,
                        double scale, const std::string& what) {
  EXPECT_LE((actual - expected).norm(), 1e-12 * scale)
      << what << ": " << actual.transpose() << " vs " << expected.transpose();
}

void expect_scene_is(const std::string& name, const testing::BenchSceneBody& written) {
  const std::filesystem::path file =
      std::filesystem::path(TUMBLE_SOURCE_DIR) / "assets/scenes" / name;
  const SceneDescription description = load_scene(file);
  EXPECT_EQ(description.duration, written.duration);
  EXPECT_EQ(description.dt, written.dt);
  const CompiledScene compiled = compile_scene(description);
  ASSERT_EQ(compiled.bodies.size(), 1u);
  const engine::BodyModel& body = compiled.bodies[0];
  const engine::BodyState& state = compiled.initial[0];
  EXPECT_NEAR(body.mass, written.body.mass, 1e-15 * body.mass);
  expect_near_vector(body.moments, written.body.moments, body.moments.norm(), "moments");
  EXPECT_EQ(body.pivoted, written.body.pivoted);
  expect_near_vector(body.pivot, written.body.pivot, 1.0, "pivot");
  expect_near_vector(body.center_offset, written.body.center_offset, 1.0, "centre offset");
  ASSERT_EQ(body.forces.size(), written.body.forces.size());
  for (std::size_t i = 0; i < body.forces.size(); ++i) {
    ASSERT_TRUE(std::holds_alternative<engine::Gravity>(body.forces[i]));
    expect_near_vector(std::get<engine::Gravity>(body.forces[i]).acceleration,
                       std::get<engine::Gravity>(written.body.forces[i]).acceleration, 10.0,
                       "gravity");
  }
  EXPECT_LE(engine::orientation_angle(state.orientation, written.initial.orientation), 1e-15);
  expect_near_vector(state.angular_momentum, written.initial.angular_momentum,
                     state.angular_momentum.norm(), "angular momentum");
  expect_near_vector(state.position, written.initial.position, 1.0, "position");
  expect_near_vector(state.velocity, written.initial.velocity, 1.0, "velocity");
}

TEST(BenchSceneBodies, TheTHandleIsTheScenes) {
  expect_scene_is("t_handle_flip.json", testing::t_handle_flip_body());
}

TEST(BenchSceneBodies, TheHeavyTopIsTheScenes) {
  expect_scene_is("heavy_top.json", testing::heavy_top_body());
}

}  // namespace
}  // namespace tumble::app
