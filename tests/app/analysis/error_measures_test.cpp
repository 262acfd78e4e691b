// The measurement half of `tumble bench`: the sampling grid, relative differences and the
// error meter (geodesic orientation angle, relative omega and L errors, invariant drift)
// against hand-made references. How a reference is computed is not tested here.
#include "app/analysis/error_measures.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace tumble::app {
namespace {

using engine::BodyModel;
using engine::BodyState;

Eigen::Quaterniond turn(double angle, const Eigen::Vector3d& axis) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis.normalized()));
}

/// A unit sphere-like body (J = 1): w = L, E = |L|^2 / 2 at rest in translation.
BodyModel unit_body() {
  BodyModel body;
  body.moments = {1.0, 1.0, 1.0};
  return body;
}

BodyState state_with(const Eigen::Quaterniond& orientation, const Eigen::Vector3d& momentum) {
  BodyState state;
  state.orientation = orientation;
  state.angular_momentum = momentum;
  return state;
}

ReferenceState reference_at(const Eigen::Quaterniond& orientation, const Eigen::Vector3d& omega,
                            const Eigen::Vector3d& momentum) {
  return {orientation, omega, momentum};
}

/// The orientation error the meter reports for `state` against a reference at `expected`.
double orientation_error(const Eigen::Quaterniond& expected, const Eigen::Quaterniond& actual) {
  const std::vector<BodyModel> bodies = {unit_body()};
  const std::vector<BodyState> initial = {state_with(expected, {1, 0, 0})};
  Reference reference;
  reference.samples = {{reference_at(expected, {1, 0, 0}, {1, 0, 0})}};
  ErrorMeter meter(bodies, initial, reference);
  meter.observe(1, {state_with(actual, {1, 0, 0})});
  return meter.figures().orientation_final;
}

TEST(SampleGrid, CountsAndTimesOfAnEvenDivision) {
  const SampleGrid grid{0.1, 1.0};
  EXPECT_EQ(grid.count(), 10u);
  EXPECT_DOUBLE_EQ(grid.time(1), 0.1);
  EXPECT_DOUBLE_EQ(grid.time(3), 0.3);
  EXPECT_EQ(grid.time(10), 1.0);  // exactly the duration, not 10 * 0.1
}

TEST(SampleGrid, RoundingOfTheQuotientAddsNoSample) {
  // 0.3 / 0.1 = 2.9999999999999996 in doubles: three samples, the last at 0.3.
  const SampleGrid grid{0.1, 0.3};
  EXPECT_EQ(grid.count(), 3u);
  EXPECT_EQ(grid.time(3), 0.3);
}

TEST(SampleGrid, AShortLastIntervalEndsAtTheDuration) {
  const SampleGrid grid{0.1, 1.05};
  EXPECT_EQ(grid.count(), 11u);
  EXPECT_DOUBLE_EQ(grid.time(10), 1.0);
  EXPECT_EQ(grid.time(11), 1.05);
}

TEST(RelativeDifference, RelativeToTheSecondArgument) {
  // a - b = (1, -1, -2), |b| = 5.
  EXPECT_DOUBLE_EQ(relative_difference({1, 2, 2}, {0, 3, 4}), std::sqrt(6.0) / 5.0);
  EXPECT_DOUBLE_EQ(relative_difference({0, 3, 4}, {1, 2, 2}), std::sqrt(6.0) / 3.0);
  EXPECT_EQ(relative_difference({1, 2, 3}, {1, 2, 3}), 0.0);
}

TEST(RelativeDifference, AbsoluteWhenTheReferenceIsZero) {
  EXPECT_DOUBLE_EQ(relative_difference({3, 4, 0}, Eigen::Vector3d::Zero()), 5.0);
  EXPECT_EQ(relative_difference(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()), 0.0);
}

TEST(ErrorMeterOrientation, GeodesicAngleOfHandMadeRotations) {
  EXPECT_EQ(orientation_error(Eigen::Quaterniond::Identity(), Eigen::Quaterniond::Identity()), 0.0);
  EXPECT_NEAR(orientation_error(Eigen::Quaterniond::Identity(), turn(0.3, {0, 0, 1})), 0.3, 1e-15);
  EXPECT_NEAR(orientation_error(Eigen::Quaterniond::Identity(), turn(2.5, {1, 2, 2})), 2.5, 1e-14);
  // Relative to a turned reference: 0.7 then 0.2 more about the same axis is 0.2 apart.
  EXPECT_NEAR(orientation_error(turn(0.7, {1, 1, 0}), turn(0.9, {1, 1, 0})), 0.2, 1e-14);
  // Two quarter turns about perpendicular axes: cos(angle / 2) = cos^2(pi / 4) = 1 / 2.
  EXPECT_NEAR(orientation_error(turn(M_PI / 2, {1, 0, 0}), turn(M_PI / 2, {0, 1, 0})),
              2.0 * M_PI / 3.0, 1e-14);
}

TEST(ErrorMeterOrientation, TheLongWayRoundIsTheShortAngle) {
  // A turn by 3.5 rad is a turn by 2 pi - 3.5 the other way: the geodesic angle is at most pi.
  EXPECT_NEAR(orientation_error(Eigen::Quaterniond::Identity(), turn(3.5, {0, 1, 0})),
              2.0 * M_PI - 3.5, 1e-14);
  EXPECT_NEAR(orientation_error(Eigen::Quaterniond::Identity(), turn(M_PI, {0, 1, 0})), M_PI,
              1e-14);
}

TEST(ErrorMeterOrientation, QAndMinusQAreTheSameOrientation) {
  const Eigen::Quaterniond q = turn(0.4, {1, -2, 0.5});
  const Eigen::Quaterniond minus_q(-q.coeffs());
  EXPECT_NEAR(orientation_error(q, minus_q), 0.0, 1e-15);
  EXPECT_NEAR(orientation_error(Eigen::Quaterniond::Identity(), minus_q), 0.4, 1e-15);
  EXPECT_NEAR(orientation_error(minus_q, Eigen::Quaterniond::Identity()), 0.4, 1e-15);
}

TEST(ErrorMeterOrientation, TinyAnglesKeepTheirDigitsWhereAcosWouldGiveZero) {
  for (const double angle : {1e-9, 3e-12, 1e-15}) {
    const Eigen::Quaterniond q = turn(angle, {0, 0, 1});
    // acos of the real part would round to 0 here.
    ASSERT_EQ(2.0 * std::acos(std::min(1.0, std::abs(q.w()))), 0.0) << angle;
    EXPECT_NEAR(orientation_error(Eigen::Quaterniond::Identity(), q), angle, 1e-6 * angle);
    // Against a turned reference, a^* (a q) leaves rounding of ~1e-16 in the vector part.
    EXPECT_NEAR(orientation_error(turn(1.0, {1, 0, 0}), turn(1.0, {1, 0, 0}) * q), angle, 1e-15);
  }
}

TEST(ErrorMeter, OmegaAndMomentumErrorsAreRelativeToTheReference) {
  BodyModel body;
  body.moments = {1.0, 2.0, 4.0};
  const std::vector<BodyModel> bodies = {body};
  // L = (1, 2, 4) with the identity orientation turns at w = J^-1 L = (1, 1, 1).
  const BodyState state = state_with(Eigen::Quaterniond::Identity(), {1, 2, 4});
  Reference reference;
  reference.samples = {{reference_at(Eigen::Quaterniond::Identity(), {1, 1, 2}, {1, 2, 2})}};
  ErrorMeter meter(bodies, {state}, reference);
  meter.observe(1, {state});
  const ErrorFigures& f = meter.figures();
  EXPECT_DOUBLE_EQ(f.omega_final, 1.0 / std::sqrt(6.0));  // |(0, 0, -1)| / |(1, 1, 2)|
  EXPECT_DOUBLE_EQ(f.momentum_final, 2.0 / 3.0);          // |(0, 0, 2)| / |(1, 2, 2)|
  EXPECT_EQ(f.orientation_final, 0.0);
  EXPECT_EQ(f.energy_drift_max, 0.0);  // the initial state itself
  EXPECT_EQ(f.momentum_norm_drift_max, 0.0);
  EXPECT_EQ(f.samples, 1u);
}

TEST(ErrorMeter, InvariantDriftsAreRelativeToTheInitialValues) {
  const std::vector<BodyModel> bodies = {unit_body()};
  const BodyState initial = state_with(Eigen::Quaterniond::Identity(), {0, 0, 2});  // E0 = 2
  Reference reference;
  reference.samples = {{reference_at(Eigen::Quaterniond::Identity(), {0, 0, 2}, {0, 0, 2})}};
  ErrorMeter meter(bodies, {initial}, reference);
  meter.observe(1, {state_with(Eigen::Quaterniond::Identity(), {0, 0, 3})});  // E = 4.5
  EXPECT_DOUBLE_EQ(meter.figures().energy_drift_max, 1.25);                   // |4.5 - 2| / 2
  EXPECT_DOUBLE_EQ(meter.figures().momentum_norm_drift_max, 0.5);             // |3 - 2| / 2
  EXPECT_DOUBLE_EQ(meter.figures().momentum_final, 0.5);
}

TEST(ErrorMeter, DriftIsAbsoluteWhenTheInitialValueIsZero) {
  const std::vector<BodyModel> bodies = {unit_body()};
  const BodyState at_rest = state_with(Eigen::Quaterniond::Identity(), Eigen::Vector3d::Zero());
  Reference reference;
  reference.samples = {{reference_at(Eigen::Quaterniond::Identity(), Eigen::Vector3d::Zero(),
                                     Eigen::Vector3d::Zero())}};
  ErrorMeter meter(bodies, {at_rest}, reference);
  meter.observe(1, {state_with(Eigen::Quaterniond::Identity(), {0, 0.6, 0.8})});
  EXPECT_DOUBLE_EQ(meter.figures().energy_drift_max, 0.5);  // E = |L|^2 / 2
  EXPECT_DOUBLE_EQ(meter.figures().momentum_norm_drift_max, 1.0);
  EXPECT_DOUBLE_EQ(meter.figures().momentum_final, 1.0);
  EXPECT_DOUBLE_EQ(meter.figures().omega_final, 1.0);
}

TEST(ErrorMeter, FinalIsTheLastSampleAndMaxTheLargestOverTheRun) {
  const std::vector<BodyModel> bodies = {unit_body()};
  const BodyState initial = state_with(Eigen::Quaterniond::Identity(), {1, 0, 0});
  Reference reference;
  for (int k = 0; k < 3; ++k) {
    reference.samples.push_back(
        {reference_at(Eigen::Quaterniond::Identity(), {1, 0, 0}, {1, 0, 0})});
  }
  ErrorMeter meter(bodies, {initial}, reference);
  meter.observe(1, {state_with(turn(0.1, {0, 0, 1}), {1, 0, 0})});
  meter.observe(2, {state_with(turn(0.5, {0, 0, 1}), {1.2, 0, 0})});
  meter.observe(3, {state_with(turn(0.2, {0, 0, 1}), {1.1, 0, 0})});
  const ErrorFigures& f = meter.figures();
  EXPECT_NEAR(f.orientation_final, 0.2, 1e-15);
  EXPECT_NEAR(f.orientation_max, 0.5, 1e-15);
  EXPECT_NEAR(f.momentum_final, 0.1, 1e-15);
  EXPECT_NEAR(f.momentum_max, 0.2, 1e-15);
  EXPECT_NEAR(f.omega_final, 0.1, 1e-15);
  EXPECT_NEAR(f.omega_max, 0.2, 1e-15);
  EXPECT_NEAR(f.energy_drift_max, 0.44, 1e-15);  // (1.2^2 - 1) / 1
  EXPECT_NEAR(f.momentum_norm_drift_max, 0.2, 1e-15);
  EXPECT_EQ(f.samples, 3u);
}

TEST(ErrorMeter, EachFigureIsTheWorstBody) {
  const std::vector<BodyModel> bodies = {unit_body(), unit_body()};
  const BodyState initial = state_with(Eigen::Quaterniond::Identity(), {1, 0, 0});
  Reference reference;
  reference.samples = {{reference_at(Eigen::Quaterniond::Identity(), {1, 0, 0}, {1, 0, 0}),
                        reference_at(Eigen::Quaterniond::Identity(), {1, 0, 0}, {1, 0, 0})}};
  ErrorMeter meter(bodies, {initial, initial}, reference);
  meter.observe(1, {state_with(turn(0.3, {1, 0, 0}), {1, 0, 0}),
                    state_with(turn(0.1, {1, 0, 0}), {1.5, 0, 0})});
  EXPECT_NEAR(meter.figures().orientation_final, 0.3, 1e-15);  // body 0
  EXPECT_NEAR(meter.figures().momentum_final, 0.5, 1e-15);     // body 1
  EXPECT_NEAR(meter.figures().energy_drift_max, 1.25, 1e-15);  // body 1: (2.25 - 1) / 1
}

}  // namespace
}  // namespace tumble::app
