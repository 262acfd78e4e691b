// The simulate run as library calls (app/analysis/simulation_run.hpp): the trajectory in memory
// against the closed form of free flight, its CSV against the command's, and the checks.
#include "app/analysis/simulation_run.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sstream>

#include "app/commands/simulate_command.hpp"
#include "base/errors.hpp"
#include "support/command_test.hpp"
#include "support/run_command.hpp"
#include "support/scene_builder.hpp"

namespace tumble::app {
namespace {

using ::testing::HasSubstr;

/// A free asymmetric body flying at 0.5 m/s along x and tumbling, torque-free.
nlohmann::json flying_brick_scene() {
  return testing::SceneBuilder()
      .duration(0.5)
      .dt(0.01)
      .integrator("rk4")
      .body(testing::BodyBuilder("brick")
                .position({1, 2, 3})
                .velocity({0.5, 0, 0})
                .angular_velocity({0.01, 3.0, 0.01}, "body"))
      .json();
}

class SimulationRun : public testing::CommandTest {};

TEST_F(SimulationRun, TrajectoryFollowsFreeFlightAndKeepsTheAngularMomentum) {
  SimulateOptions options;
  options.scene = write_scene(flying_brick_scene());
  const Trajectory trajectory = run_simulation(options);
  // 50 steps of 0.01 s, every one recorded, and the start.
  ASSERT_EQ(trajectory.times.size(), 51u);
  ASSERT_EQ(trajectory.bodies.size(), 1u);
  EXPECT_EQ(trajectory.summary.steps, 50u);
  EXPECT_FALSE(trajectory.summary.blow_up);
  const double momentum0 = trajectory.sample(0, 0).angular_momentum.norm();
  for (std::size_t k = 0; k < trajectory.times.size(); ++k) {
    const double t = trajectory.times[k];
    EXPECT_NEAR(t, 0.01 * static_cast<double>(k), 1e-12);
    const BodySample sample = trajectory.sample(k, 0);
    // No force: x(t) = x0 + v t exactly as far as rounding goes.
    EXPECT_NEAR(sample.position.x(), 1.0 + 0.5 * t, 1e-12);
    EXPECT_NEAR(sample.position.y(), 2.0, 1e-12);
    EXPECT_NEAR(sample.position.z(), 3.0, 1e-12);
    EXPECT_NEAR(sample.orientation.norm(), 1.0, 1e-12);
    // No torque: the world angular momentum stays what it was.
    EXPECT_NEAR(sample.angular_momentum.norm(), momentum0, 1e-9 * momentum0);
  }
}

TEST_F(SimulationRun, CsvOfTheTrajectoryIsTheCommandsByteForByte) {
  SimulateOptions options;
  options.scene = write_scene(flying_brick_scene());
  options.every = 7;
  options.csv = dir_ / "command.csv";
  std::ostringstream out, err;
  ASSERT_EQ(run_simulate(options, out, err), 0) << err.str();
  options.csv.reset();
  const Trajectory trajectory = run_simulation(options);
  // Steps 0, 7, ..., 49 and the last (50).
  EXPECT_EQ(trajectory.times.size(), 9u);
  write_trajectory_csv(trajectory, dir_ / "library.csv");
  const std::string command = testing::read_text(dir_ / "command.csv");
  EXPECT_FALSE(command.empty());
  EXPECT_EQ(testing::read_text(dir_ / "library.csv"), command);
}

TEST_F(SimulationRun, InterruptedRunStopsAtItsFirstPoll) {
  SimulateOptions options;
  options.scene = write_scene(flying_brick_scene());
  const Trajectory trajectory = run_simulation(options, [] { return true; });
  // The poll comes before the first step: only the start is recorded.
  EXPECT_EQ(trajectory.times.size(), 1u);
  EXPECT_EQ(trajectory.summary.steps, 0u);
}

TEST_F(SimulationRun, BadOptionIsAnInputErrorNamingIt) {
  SimulateOptions options;
  options.scene = write_scene(flying_brick_scene());
  options.every = 0;
  try {
    run_simulation(options);
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_THAT(error.what(), HasSubstr("--every: expected a whole number >= 1, got 0"));
  }
}

}  // namespace
}  // namespace tumble::app
