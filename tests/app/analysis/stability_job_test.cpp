// `tumble stability` as library calls (app/analysis/stability_job.hpp): a scene case's rows in
// the sweep's order, their errors against the exact torque-free solution computed here, and a
// shard's runs.
#include "app/analysis/stability_job.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sstream>

#include "base/errors.hpp"
#include "support/command_test.hpp"
#include "support/scene_builder.hpp"
#include "support/torque_free_brick.hpp"

namespace tumble::app {
namespace {

using ::testing::HasSubstr;

class StabilityJob : public testing::CommandTest {};

TEST_F(StabilityJob, SceneCaseRowsComeInSweepOrderAndBoundTheExactError) {
  StabilityOptions options;
  options.scenes = {write_scene(testing::torque_free_brick_scene())};
  options.integrators = "rk4";
  options.dts = "0.01,0.02";
  const std::vector<StabilityRun> runs = run_stability_rows(options);
  ASSERT_EQ(runs.size(), 2u);
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const StabilityRun& run = runs[i];
    EXPECT_EQ(run.integrator, "rk4");
    EXPECT_DOUBLE_EQ(run.dt, i == 0 ? 0.01 : 0.02);
    EXPECT_EQ(run.outcome, StabilityOutcome::kStable) << outcome_name(run.outcome);
    EXPECT_EQ(run.steps, run.total_steps);
    ASSERT_TRUE(run.orientation_error);
    // The largest error over the compared instants, the end among them.
    const double final_error = testing::exact_final_error(options.scenes[0], "rk4", run.dt);
    EXPECT_GE(*run.orientation_error, final_error * (1.0 - 1e-9));
    EXPECT_LT(*run.orientation_error, 1e-4);
  }
  // Fourth order: doubling the step multiplies the error by about 16.
  EXPECT_GT(*runs[1].orientation_error / *runs[0].orientation_error, 10.0);
}

TEST_F(StabilityJob, ShardKeepsEveryNthRunOfTheSweep) {
  StabilityOptions options;
  options.scenes = {write_scene(testing::torque_free_brick_scene())};
  options.integrators = "rk4,midpoint";
  options.dts = "0.01,0.02";
  options.shard = "1/2";
  const std::vector<StabilityRun> runs = run_stability_rows(options);
  // Runs 0..3 are rk4 0.01, rk4 0.02, midpoint 0.01, midpoint 0.02: the shard has 1 and 3.
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_EQ(runs[0].integrator, "rk4");
  EXPECT_DOUBLE_EQ(runs[0].dt, 0.02);
  EXPECT_EQ(runs[1].integrator, "midpoint");
  EXPECT_DOUBLE_EQ(runs[1].dt, 0.02);
}

TEST_F(StabilityJob, UnknownIntegratorIsAnInputErrorNamingIt) {
  StabilityOptions options;
  options.scenes = {write_scene(testing::torque_free_brick_scene())};
  options.integrators = "rk5";
  try {
    run_stability_rows(options);
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_THAT(error.what(), HasSubstr("rk5"));
  }
}

TEST_F(StabilityJob, SuitesAreListedOneALine) {
  std::ostringstream out;
  list_stability_suites(out);
  for (const SuiteListing& suite : stability_suite_listing()) {
    EXPECT_THAT(out.str(), HasSubstr(suite.name + "  " + suite.description + "\n"));
  }
}

}  // namespace
}  // namespace tumble::app
