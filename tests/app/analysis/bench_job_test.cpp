// `tumble bench` as library calls (app/analysis/bench_job.hpp): the rows against the exact
// torque-free solution computed here from the engine, and the observed order of rk4.
#include "app/analysis/bench_job.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "base/errors.hpp"
#include "support/command_test.hpp"
#include "support/scene_builder.hpp"
#include "support/torque_free_brick.hpp"

namespace tumble::app {
namespace {

using ::testing::HasSubstr;

using testing::exact_final_error;

class BenchJob : public testing::CommandTest {};

TEST_F(BenchJob, RowsAreTheErrorsAgainstTheExactSolutionAndShowFourthOrder) {
  BenchOptions options;
  options.scenes = {write_scene(testing::torque_free_brick_scene())};
  options.integrators = "rk4";
  options.dts = "0.02,0.01";
  options.repeat = "1";
  const std::optional<BenchOutcome> outcome = run_bench_rows(options);
  ASSERT_TRUE(outcome);
  ASSERT_EQ(outcome->cases.size(), 2u);
  ASSERT_EQ(outcome->results.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    const BenchCase& c = outcome->cases[i];
    const CaseResult& r = outcome->results[i];
    EXPECT_EQ(c.integrator, "rk4");
    EXPECT_FALSE(r.blow_up_time);
    EXPECT_EQ(r.steps, r.total_steps);
    EXPECT_EQ(r.seconds.size(), 1u);
    const double expected = exact_final_error(options.scenes[0], "rk4", c.dt);
    EXPECT_NEAR(r.errors.orientation_final, expected, 1e-9 * expected + 1e-15) << c.dt;
  }
  EXPECT_DOUBLE_EQ(outcome->cases[0].dt, 0.02);
  EXPECT_DOUBLE_EQ(outcome->cases[1].dt, 0.01);
  // Halving the step divides a fourth-order error by about 2^4.
  const double order = std::log2(outcome->results[0].errors.orientation_final /
                                 outcome->results[1].errors.orientation_final);
  EXPECT_NEAR(order, 4.0, 0.3);
}

TEST_F(BenchJob, ShardRunsEveryNthCaseOfThePlan) {
  BenchOptions options;
  options.scenes = {write_scene(testing::torque_free_brick_scene())};
  options.integrators = "rk4,midpoint";
  options.dts = "0.02,0.01";
  options.repeat = "1";
  options.shard = "1/2";
  BenchRun run = bench_settings(options);
  plan_bench_run(options, run);
  EXPECT_EQ(run.total, 4u);
  EXPECT_EQ(run.items, (std::vector<std::size_t>{1, 3}));
  ASSERT_EQ(run.outcome.cases.size(), 2u);
  EXPECT_DOUBLE_EQ(run.outcome.cases[0].dt, 0.01);
  EXPECT_DOUBLE_EQ(run.outcome.cases[1].dt, 0.01);
  EXPECT_EQ(run.outcome.cases[0].integrator, "rk4");
  EXPECT_EQ(run.outcome.cases[1].integrator, "midpoint");
}

TEST_F(BenchJob, BadRepeatIsAnInputErrorNamingIt) {
  BenchOptions options;
  options.scenes = {write_scene(testing::torque_free_brick_scene())};
  options.repeat = "0";
  try {
    bench_settings(options);
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_THAT(error.what(), HasSubstr("--repeat"));
  }
}

TEST_F(BenchJob, StoppedRunGivesNoRows) {
  BenchOptions options;
  options.scenes = {write_scene(testing::torque_free_brick_scene())};
  options.integrators = "rk4";
  options.dts = "0.01";
  options.repeat = "1";
  EXPECT_FALSE(run_bench_rows(options, [] { return true; }));
}

}  // namespace
}  // namespace tumble::app
