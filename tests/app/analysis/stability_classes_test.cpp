// The classification rules of `tumble stability`, each with its boundary.
#include "app/analysis/stability_classes.hpp"

#include <gtest/gtest.h>

#include <string>

namespace tumble::app {
namespace {

constexpr double kT = 1e-3;  // the threshold these tests classify against

InvariantChanges energy_only() {
  InvariantChanges c;
  c.energy_applies = true;
  return c;
}

InvariantChanges momentum_only() {
  InvariantChanges c;
  c.momentum_applies = true;
  return c;
}

/// An invariant that lost `loss` and stayed between -late_high and -late_low at the end.
InvariantChanges energy_lost(double loss, double late_low, double late_high) {
  InvariantChanges c = energy_only();
  c.energy_max_loss = loss;
  c.energy_final = -late_low;
  c.energy_late_min = -late_high;
  c.energy_late_max = -late_low;
  return c;
}

TEST(OutcomeName, AsWrittenInTheOutputs) {
  EXPECT_STREQ(outcome_name(StabilityOutcome::kStable), "stable");
  EXPECT_STREQ(outcome_name(StabilityOutcome::kDrifting), "drifting");
  EXPECT_STREQ(outcome_name(StabilityOutcome::kDamped), "damped");
  EXPECT_STREQ(outcome_name(StabilityOutcome::kBlewUp), "blew up");
  EXPECT_STREQ(outcome_name(StabilityOutcome::kUnchecked), "unchecked");
  EXPECT_STREQ(outcome_name(StabilityOutcome::kSkipped), "skipped");
}

TEST(Classify, TheDefaultThresholdIsOnePerMille) {
  EXPECT_EQ(kStabilityDriftThreshold, 1e-3);
}

TEST(Classify, Rule1ABlowUpWinsOverEverything) {
  EXPECT_EQ(classify(true, energy_only(), kT), StabilityOutcome::kBlewUp);
  EXPECT_EQ(classify(true, InvariantChanges{}, kT), StabilityOutcome::kBlewUp);
}

TEST(Classify, Rule2NoInvariantIsUncheckedWhateverTheNumbers) {
  InvariantChanges c;
  c.energy_max_gain = 10.0;  // ignored: energy does not apply
  c.momentum_max_loss = 10.0;
  EXPECT_EQ(classify(false, c, kT), StabilityOutcome::kUnchecked);
}

TEST(Classify, Rule3StableUpToAndIncludingTheThreshold) {
  InvariantChanges c = energy_only();
  c.energy_max_gain = kT;
  c.energy_max_loss = kT;
  EXPECT_EQ(classify(false, c, kT), StabilityOutcome::kStable);
  c.energy_max_gain = 1.0000001 * kT;
  EXPECT_EQ(classify(false, c, kT), StabilityOutcome::kDrifting);
  EXPECT_EQ(classify(false, momentum_only(), kT), StabilityOutcome::kStable);
}

TEST(Classify, Rule3EveryApplicableInvariantCounts) {
  InvariantChanges c = energy_only();
  c.momentum_applies = true;
  c.momentum_max_gain = 2 * kT;
  EXPECT_EQ(classify(false, c, kT), StabilityOutcome::kDrifting);
  c.momentum_applies = false;  // the same numbers, not an invariant: ignored
  EXPECT_EQ(classify(false, c, kT), StabilityOutcome::kStable);
}

TEST(Classify, Rule4APersistentLossIsDamped) {
  // Lost 5%, ending between -5% and -4%: a swing of 1% < half of 4%.
  EXPECT_EQ(classify(false, energy_lost(0.05, 0.04, 0.05), kT), StabilityOutcome::kDamped);
}

TEST(Classify, Rule4TheLateMaximumMustBeBelowMinusTheThreshold) {
  // Ends at exactly -threshold: not below it.
  EXPECT_EQ(classify(false, energy_lost(0.01, kT, kT), kT), StabilityOutcome::kDrifting);
  EXPECT_EQ(classify(false, energy_lost(0.01, 1.01 * kT, 1.01 * kT), kT),
            StabilityOutcome::kDamped);
}

TEST(Classify, Rule4AWideSwingBelowTheStartIsNotDamping) {
  // Late max -1/16: a swing of exactly half of it (1/32, all exact in binary) is not less.
  EXPECT_EQ(classify(false, energy_lost(0.1, 0.0625, 0.09375), kT), StabilityOutcome::kDrifting);
  EXPECT_EQ(classify(false, energy_lost(0.1, 0.0625, 0.0937), kT), StabilityOutcome::kDamped);
}

TEST(Classify, Rule4AGainBeyondTheThresholdAnywhereIsDrifting) {
  InvariantChanges c = energy_lost(0.05, 0.04, 0.05);
  c.energy_max_gain = kT;
  EXPECT_EQ(classify(false, c, kT), StabilityOutcome::kDamped);
  c.energy_max_gain = 2 * kT;
  EXPECT_EQ(classify(false, c, kT), StabilityOutcome::kDrifting);
  // A gain of the other invariant counts too.
  c.energy_max_gain = 0.0;
  c.momentum_applies = true;
  c.momentum_max_gain = 2 * kT;
  EXPECT_EQ(classify(false, c, kT), StabilityOutcome::kDrifting);
}

TEST(Classify, Rule4EitherInvariantMayShowTheLoss) {
  InvariantChanges c = momentum_only();
  c.momentum_max_loss = 0.1;
  c.momentum_late_min = -0.1;
  c.momentum_late_max = -0.09;
  EXPECT_EQ(classify(false, c, kT), StabilityOutcome::kDamped);
  // A loss recorded for an invariant that does not apply shows nothing.
  c.momentum_applies = false;
  c.energy_applies = true;
  c.energy_max_loss = 0.1;
  c.energy_late_max = 0.0;
  EXPECT_EQ(classify(false, c, kT), StabilityOutcome::kDrifting);
}

TEST(Classify, Rule5ALossThatRecoversIsDrifting) {
  // Lost 5% mid-run but ends near the start.
  EXPECT_EQ(classify(false, energy_lost(0.05, 0.0, 0.002), kT), StabilityOutcome::kDrifting);
}

TEST(Classify, TheThresholdArgumentIsTheOneUsed) {
  InvariantChanges c = energy_only();
  c.energy_max_gain = 0.05;
  EXPECT_EQ(classify(false, c, 0.1), StabilityOutcome::kStable);
  EXPECT_EQ(classify(false, c, 0.01), StabilityOutcome::kDrifting);
}

}  // namespace
}  // namespace tumble::app
