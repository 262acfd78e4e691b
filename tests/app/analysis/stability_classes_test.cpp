// The classification rules of `tumble stability`, each with its boundary.
#include "app/analysis/stability_classes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "app/analysis/stability_runner.hpp"
#include "app/analysis/stability_suite.hpp"
#include "engine/dynamics/integrators.hpp"

namespace tumble::app {
namespace {

constexpr double kT = 1e-3;  // the threshold these tests classify against

InvariantChanges energy_only() {
  InvariantChanges c;
  c.energy_applies = true;
  return c;
}

/// Only an orientation error, rad.
ReferenceErrors orientation(double angle) {
  return {angle, std::nullopt, std::nullopt};
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
  EXPECT_STREQ(outcome_name(StabilityOutcome::kWrong), "wrong");
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
  EXPECT_EQ(classify(true, energy_only(), kT, orientation(3.0)), StabilityOutcome::kBlewUp);
}

TEST(Classify, Rule2BoundedButFarFromTheReferenceIsWrong) {
  EXPECT_EQ(kWrongOrientationError, 0.1);
  EXPECT_EQ(kWrongEnergyChange, 1e-2);
  // Invariants kept exactly (as seed-semi-implicit keeps them on a free body), orientation off.
  EXPECT_EQ(classify(false, energy_only(), kT, orientation(0.1)), StabilityOutcome::kStable);
  EXPECT_EQ(classify(false, energy_only(), kT, orientation(0.1000001)), StabilityOutcome::kWrong);
  EXPECT_EQ(classify(false, momentum_only(), kT, orientation(2.0)), StabilityOutcome::kWrong);
  // Even with nothing else to check, a measured orientation error decides.
  EXPECT_EQ(classify(false, InvariantChanges{}, kT, orientation(2.0)), StabilityOutcome::kWrong);
  EXPECT_EQ(classify(false, InvariantChanges{}, kT, orientation(0.01)),
            StabilityOutcome::kUnchecked);
}

TEST(Classify, Rule2TheMomentumVectorAndThePositionCountToo) {
  EXPECT_EQ(kWrongMomentumError, 1e-2);
  EXPECT_EQ(kWrongPositionError, 0.1);
  // |L| kept, L turned by 1.5%: wrong (seed-semi-implicit on a nutating needle).
  EXPECT_EQ(classify(false, momentum_only(), kT, ReferenceErrors{0.05, 0.01, std::nullopt}),
            StabilityOutcome::kStable);
  EXPECT_EQ(classify(false, momentum_only(), kT, ReferenceErrors{0.05, 0.015, std::nullopt}),
            StabilityOutcome::kWrong);
  // Energy kept, the bob a tenth of its range of motion off (a phase error on a spring).
  EXPECT_EQ(classify(false, energy_only(), kT, ReferenceErrors{0.0, 0.0, 0.1}),
            StabilityOutcome::kStable);
  EXPECT_EQ(classify(false, energy_only(), kT, ReferenceErrors{0.0, 0.0, 0.11}),
            StabilityOutcome::kWrong);
}

TEST(Classify, Rule2EnergyOffByMoreThanOnePercentIsWrong) {
  InvariantChanges c = energy_only();
  c.energy_max_gain = 1e-2;  // at the boundary: drifting, not wrong
  EXPECT_EQ(classify(false, c, kT), StabilityOutcome::kDrifting);
  c.energy_max_gain = 1.0000001e-2;
  EXPECT_EQ(classify(false, c, kT), StabilityOutcome::kWrong);
  // A loss counts the same (a persistent 5% loss is wrong before it is damped).
  EXPECT_EQ(classify(false, energy_lost(0.05, 0.04, 0.05), kT), StabilityOutcome::kWrong);
  // Only the energy and the orientation decide: |L| off by 5% is drifting.
  InvariantChanges m = momentum_only();
  m.momentum_max_gain = 0.05;
  EXPECT_EQ(classify(false, m, kT, orientation(0.01)), StabilityOutcome::kDrifting);
  // An energy change recorded where the energy does not apply shows nothing.
  m.energy_max_gain = 0.5;
  EXPECT_EQ(classify(false, m, kT, orientation(0.01)), StabilityOutcome::kDrifting);
}

TEST(Classify, Rule3NoInvariantIsUncheckedWhateverTheNumbers) {
  InvariantChanges c;
  c.energy_max_gain = 10.0;  // ignored: energy does not apply
  c.momentum_max_loss = 10.0;
  EXPECT_EQ(classify(false, c, kT), StabilityOutcome::kUnchecked);
}

TEST(Classify, Rule4StableUpToAndIncludingTheThreshold) {
  InvariantChanges c = energy_only();
  c.energy_max_gain = kT;
  c.energy_max_loss = kT;
  EXPECT_EQ(classify(false, c, kT), StabilityOutcome::kStable);
  c.energy_max_gain = 1.0000001 * kT;
  EXPECT_EQ(classify(false, c, kT), StabilityOutcome::kDrifting);
  EXPECT_EQ(classify(false, momentum_only(), kT), StabilityOutcome::kStable);
}

TEST(Classify, Rule4EveryApplicableInvariantCounts) {
  InvariantChanges c = energy_only();
  c.momentum_applies = true;
  c.momentum_max_gain = 2 * kT;
  EXPECT_EQ(classify(false, c, kT), StabilityOutcome::kDrifting);
  c.momentum_applies = false;  // the same numbers, not an invariant: ignored
  EXPECT_EQ(classify(false, c, kT), StabilityOutcome::kStable);
}

TEST(Classify, Rule5APersistentLossIsDamped) {
  // Lost 0.5%, ending between -0.5% and -0.4%: a swing of 0.1% < half of 0.4%.
  EXPECT_EQ(classify(false, energy_lost(0.005, 0.004, 0.005), kT), StabilityOutcome::kDamped);
}

TEST(Classify, Rule5TheLateMaximumMustBeBelowMinusTheThreshold) {
  // Ends at exactly -threshold: not below it.
  EXPECT_EQ(classify(false, energy_lost(0.01, kT, kT), kT), StabilityOutcome::kDrifting);
  EXPECT_EQ(classify(false, energy_lost(0.01, 1.01 * kT, 1.01 * kT), kT),
            StabilityOutcome::kDamped);
}

TEST(Classify, Rule5AWideSwingBelowTheStartIsNotDamping) {
  // Late max -1/256: a swing of exactly half of it (1/512, all exact in binary) is not less.
  EXPECT_EQ(classify(false, energy_lost(0.008, 0.00390625, 0.005859375), kT),
            StabilityOutcome::kDrifting);
  EXPECT_EQ(classify(false, energy_lost(0.008, 0.00390625, 0.00585), kT),
            StabilityOutcome::kDamped);
}

TEST(Classify, Rule5AGainBeyondTheThresholdAnywhereIsDrifting) {
  InvariantChanges c = energy_lost(0.005, 0.004, 0.005);
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

TEST(Classify, Rule5EitherInvariantMayShowTheLoss) {
  InvariantChanges c = momentum_only();
  c.momentum_max_loss = 0.1;
  c.momentum_late_min = -0.1;
  c.momentum_late_max = -0.09;
  EXPECT_EQ(classify(false, c, kT), StabilityOutcome::kDamped);
  // A loss recorded for an invariant that does not apply shows nothing.
  c.momentum_applies = false;
  c.energy_applies = true;
  c.energy_max_loss = 0.005;
  c.energy_late_max = 0.0;
  EXPECT_EQ(classify(false, c, kT), StabilityOutcome::kDrifting);
}

TEST(Classify, Rule6ALossThatRecoversIsDrifting) {
  // Lost 0.5% mid-run but ends near the start.
  EXPECT_EQ(classify(false, energy_lost(0.005, 0.0, 0.002), kT), StabilityOutcome::kDrifting);
}

TEST(Classify, TheThresholdArgumentIsTheOneUsed) {
  InvariantChanges c = energy_only();
  c.energy_max_gain = 0.005;
  EXPECT_EQ(classify(false, c, 0.01), StabilityOutcome::kStable);
  EXPECT_EQ(classify(false, c, 0.001), StabilityOutcome::kDrifting);
}

/// A 2 kg bob hung on an 8 N/m spring under gravity, `height` m up (anchor and bob).
StabilityCase hanging_spring(double height) {
  StabilityCase c;
  c.name = "hanging";
  engine::BodyModel bob;
  bob.name = "bob";
  bob.mass = 2.0;
  bob.moments = Eigen::Vector3d(0.01, 0.02, 0.03);
  const Eigen::Vector3d anchor(0.0, 0.0, height);
  bob.forces = {engine::Gravity{Eigen::Vector3d(0.0, 0.0, -9.81)},
                engine::Spring{anchor, Eigen::Vector3d::Zero(), 8.0, 0.0}};
  engine::BodyState start;
  start.position = anchor + Eigen::Vector3d(0.5, 0.0, -1.0);
  c.bodies = {bob};
  c.initial = {start};
  c.duration = 10.0;
  c.dts = {0.1};
  return c;
}

const engine::IntegratorInfo& integrator(const std::string& name) {
  for (const engine::IntegratorInfo& info : engine::integrator_catalog()) {
    if (info.name == name) return info;
  }
  throw std::invalid_argument(name);
}

TEST(StabilityScale, EnergyChangesDoNotDependOnWhereTheCaseIs) {
  // The scale is k/2 |P - a|^2 + m^2 g^2 / k = 5 + 48.12 J wherever the spring hangs; |E0|
  // would be 53 J at the origin and 2e7 J a thousand kilometres up, where every change would
  // read 4e5 times smaller.
  const StabilityCase here = hanging_spring(0.0), there = hanging_spring(1e6);
  for (const char* name : {"explicit-euler", "semi-implicit-euler", "rk4"}) {
    const StabilityRun a =
        run_stability_case(here, integrator(name), 0.1, stability_reference(here));
    const StabilityRun b =
        run_stability_case(there, integrator(name), 0.1, stability_reference(there));
    EXPECT_EQ(a.outcome, b.outcome) << name;
    EXPECT_GT(a.changes.energy_max_gain + a.changes.energy_max_loss, 1e-7) << name;
    EXPECT_NEAR(b.changes.energy_max_gain, a.changes.energy_max_gain,
                1e-6 * a.changes.energy_max_gain + 1e-9)
        << name;
    EXPECT_NEAR(b.changes.energy_max_loss, a.changes.energy_max_loss,
                1e-6 * a.changes.energy_max_loss + 1e-9)
        << name;
  }
  // Explicit Euler gains energy on an oscillator by (1 + (wn dt)^2) per step: 4% a step.
  const StabilityOutcome explicit_euler =
      run_stability_case(there, integrator("explicit-euler"), 0.1, stability_reference(there))
          .outcome;
  EXPECT_TRUE(explicit_euler == StabilityOutcome::kWrong ||
              explicit_euler == StabilityOutcome::kBlewUp)
      << outcome_name(explicit_euler);
}

TEST(StabilityScale, TheHeavyTopsScaleIsTheSwingOfItsGravity) {
  // The origin-free scale less the separately conserved spin energy: m g l (1 + cos 0.3).
  const StabilityCase top = stability_suite("quick").cases[1];
  ASSERT_EQ(top.name, "heavy-top");
  ASSERT_TRUE(top.energy_scale.has_value());
  EXPECT_NEAR(*top.energy_scale, 9.81 * 0.5 * (1.0 + std::cos(0.3)), 1e-11);
}

}  // namespace
}  // namespace tumble::app
