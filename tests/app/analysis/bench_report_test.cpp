// observed_order: the least-squares order of an integrator on a scene, from the runs in the
// asymptotic range.
#include "app/analysis/bench_report.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>

namespace tumble::app {
namespace {

/// Adds a run of `integrator` on `scene` at step `dt` whose final orientation error is `error`.
void add_run(BenchOutcome& outcome, std::size_t scene, const std::string& integrator, double dt,
             double error, std::optional<double> tolerance = std::nullopt, bool blew_up = false,
             std::size_t steps = 0) {
  BenchCase c;
  c.scene = scene;
  c.integrator = integrator;
  c.dt = dt;
  c.tolerance = tolerance;
  outcome.cases.push_back(c);
  CaseResult r;
  r.steps = steps;
  r.errors.orientation_final = error;
  if (blew_up) r.blow_up_time = 1.0;
  outcome.results.push_back(r);
}

BenchOutcome two_scenes() {
  BenchOutcome outcome;
  outcome.scenes.resize(2);
  return outcome;
}

TEST(ObservedOrder, ExactPowerLawGivesItsExponent) {
  BenchOutcome outcome = two_scenes();
  for (const double dt : {0.1, 0.05, 0.025, 0.0125})
    add_run(outcome, 0, "rk4", dt, 3.0 * std::pow(dt, 4));
  const OrderFit fit = observed_order(outcome, 0, "rk4");
  ASSERT_TRUE(fit.slope.has_value());
  EXPECT_NEAR(*fit.slope, 4.0, 1e-12);
  EXPECT_EQ(fit.used, 4u);
  EXPECT_EQ(fit.dropped, 0u);
}

TEST(ObservedOrder, LeastSquaresOverScatteredPoints) {
  // log errors 0, 1, 3 (times log 2) at log dt 0, 1, 2 (times log 2): slope 3/2.
  BenchOutcome outcome = two_scenes();
  add_run(outcome, 0, "midpoint", 0.01, 0.01);
  add_run(outcome, 0, "midpoint", 0.02, 0.02);
  add_run(outcome, 0, "midpoint", 0.04, 0.08);
  const OrderFit fit = observed_order(outcome, 0, "midpoint");
  ASSERT_TRUE(fit.slope.has_value());
  EXPECT_NEAR(*fit.slope, 1.5, 1e-12);
}

TEST(ObservedOrder, OnlyTheRunsOfThatIntegratorOnThatScene) {
  BenchOutcome outcome = two_scenes();
  add_run(outcome, 0, "splitting", 0.1, 1e-2);
  add_run(outcome, 1, "splitting", 0.05, 1e-9);  // another scene
  add_run(outcome, 0, "rk4", 0.05, 1e-9);        // another integrator
  add_run(outcome, 0, "splitting", 0.05, 2.5e-3);
  const OrderFit fit = observed_order(outcome, 0, "splitting");
  ASSERT_TRUE(fit.slope.has_value());
  EXPECT_NEAR(*fit.slope, 2.0, 1e-12);
  EXPECT_EQ(fit.used, 2u);
  EXPECT_EQ(fit.dropped, 0u);
}

TEST(ObservedOrder, BlowUpsRoundingFloorAndSaturationAreDropped) {
  BenchOutcome outcome = two_scenes();
  add_run(outcome, 0, "rk4", 0.4, 0.1, std::nullopt, /*blew_up=*/true);
  add_run(outcome, 0, "rk4", 0.2, kSaturation);  // saturated: not below 0.5
  add_run(outcome, 0, "rk4", 0.1, 1e-4);
  add_run(outcome, 0, "rk4", 0.05, 1e-4 / 16);
  add_run(outcome, 0, "rk4", 0.001, kRoundingFloor);  // at the floor: not above it
  add_run(outcome, 0, "rk4", 0.0005, std::nan(""));
  const OrderFit fit = observed_order(outcome, 0, "rk4");
  ASSERT_TRUE(fit.slope.has_value());
  EXPECT_NEAR(*fit.slope, 4.0, 1e-12);
  EXPECT_EQ(fit.used, 2u);
  EXPECT_EQ(fit.dropped, 4u);
}

TEST(ObservedOrder, WhenEveryRunSaturatesTheFitUsesThemAll) {
  BenchOutcome outcome = two_scenes();
  add_run(outcome, 0, "seed-semi-implicit", 0.1, 1.0);
  add_run(outcome, 0, "seed-semi-implicit", 0.05, 1.0);
  add_run(outcome, 0, "seed-semi-implicit", 0.025, 1.0);
  const OrderFit fit = observed_order(outcome, 0, "seed-semi-implicit");
  ASSERT_TRUE(fit.slope.has_value());
  EXPECT_NEAR(*fit.slope, 0.0, 1e-12);
  EXPECT_EQ(fit.used, 3u);
  EXPECT_EQ(fit.dropped, 0u);
}

TEST(ObservedOrder, AdaptiveRunsAreFittedAgainstTheirTolerance) {
  BenchOutcome outcome = two_scenes();
  // The same output step, tolerances 1e-6 and 1e-8, errors proportional to them.
  add_run(outcome, 0, "dopri", 0.1, 5e-6, 1e-6);
  add_run(outcome, 0, "dopri", 0.1, 5e-8, 1e-8);
  const OrderFit fit = observed_order(outcome, 0, "dopri");
  ASSERT_TRUE(fit.slope.has_value());
  EXPECT_NEAR(*fit.slope, 1.0, 1e-12);
}

TEST(ObservedOrder, FewerThanTwoPointsOrOneStepGiveNoSlope) {
  BenchOutcome outcome = two_scenes();
  add_run(outcome, 0, "rk4", 0.1, 1e-3);
  OrderFit fit = observed_order(outcome, 0, "rk4");
  EXPECT_FALSE(fit.slope.has_value());
  EXPECT_EQ(fit.used, 1u);
  add_run(outcome, 0, "rk4", 0.1, 2e-3);  // the same dt twice: no spread in x
  fit = observed_order(outcome, 0, "rk4");
  EXPECT_FALSE(fit.slope.has_value());
  EXPECT_EQ(fit.used, 2u);
  EXPECT_FALSE(observed_order(outcome, 0, "midpoint").slope.has_value());
  EXPECT_EQ(observed_order(outcome, 0, "midpoint").used, 0u);
}

// Rounding: an integrator exact for the problem (free-rotor without torques) has errors that
// grow with the number of steps (today's T-handle shows a "slope" of -1.07). Errors that do
// not fall with the step while each is below 1e3 eps per step of its run are not an order.
TEST(ObservedOrder, ErrorsGrowingWithTheStepsAtRoundingAreNotAnOrder) {
  BenchOutcome outcome = two_scenes();
  // 5 s at dt 0.04 ... 0.005: 125 ... 1000 steps, errors 1.6e-13 per step (below 2.2e-13).
  for (const double dt : {0.04, 0.02, 0.01, 0.005}) {
    const auto steps = static_cast<std::size_t>(std::lround(5.0 / dt));
    add_run(outcome, 0, "free-rotor", dt, 1.6e-13 * static_cast<double>(steps), std::nullopt, false,
            steps);
  }
  const OrderFit fit = observed_order(outcome, 0, "free-rotor");
  EXPECT_FALSE(fit.slope.has_value());
  EXPECT_TRUE(fit.at_rounding);
  EXPECT_EQ(fit.used, 4u);
  // The same trend ten times larger is above the rounding level: a (negative) slope it is.
  BenchOutcome larger = two_scenes();
  for (const double dt : {0.04, 0.02, 0.01, 0.005}) {
    const auto steps = static_cast<std::size_t>(std::lround(5.0 / dt));
    add_run(larger, 0, "free-rotor", dt, 1.6e-12 * static_cast<double>(steps), std::nullopt, false,
            steps);
  }
  const OrderFit above = observed_order(larger, 0, "free-rotor");
  ASSERT_TRUE(above.slope.has_value());
  EXPECT_NEAR(*above.slope, -1.0, 1e-12);
  EXPECT_FALSE(above.at_rounding);
}

TEST(ObservedOrder, ConvergingErrorsBelowTheRoundingLevelKeepTheirOrder) {
  // Falling errors are an order even where they are small (the rule needs slope <= 0).
  BenchOutcome outcome = two_scenes();
  for (const double dt : {0.04, 0.02})
    add_run(outcome, 0, "rk4", dt, 1e-7 * std::pow(dt / 0.04, 4), std::nullopt, false, 1000000);
  const OrderFit fit = observed_order(outcome, 0, "rk4");
  ASSERT_TRUE(fit.slope.has_value());
  EXPECT_NEAR(*fit.slope, 4.0, 1e-12);
  EXPECT_FALSE(fit.at_rounding);
}

TEST(ObservedOrder, EveryRunAtTheFloorOrExactlyZeroIsAtRounding) {
  BenchOutcome outcome = two_scenes();
  add_run(outcome, 0, "free-rotor", 0.04, 0.0);
  add_run(outcome, 0, "free-rotor", 0.02, 3e-12);
  const OrderFit fit = observed_order(outcome, 0, "free-rotor");
  EXPECT_FALSE(fit.slope.has_value());
  EXPECT_TRUE(fit.at_rounding);
  EXPECT_EQ(fit.dropped, 2u);
  // A lone run blown up is not rounding, just nothing to fit.
  add_run(outcome, 0, "explicit-euler", 0.04, 0.0, std::nullopt, /*blew_up=*/true);
  EXPECT_FALSE(observed_order(outcome, 0, "explicit-euler").at_rounding);
}

}  // namespace
}  // namespace tumble::app
