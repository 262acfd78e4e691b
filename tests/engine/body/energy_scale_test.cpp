// The origin-free energy scale and the blow-up rule built on it (engine/PHYSICS.md §6): the scale
// against closed forms (a spring is its own swing, a pivoted top's drop to its lowest point, the
// largest kinetic energy of an exact fall), and the same blow-up step, under every integrator,
// wherever the scene is put (along gravity and across it, 100 m and 10^6 m away).
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "base/errors.hpp"
#include "engine/body/rigid_body.hpp"
#include "engine/dynamics/integrators.hpp"
#include "engine/simulation/simulation.hpp"

namespace tumble::engine {
namespace {

const Eigen::Vector3d kG(0.0, 0.0, -9.81);

/// A 2 kg bob on an 8 N/m spring (wn = 2 rad/s) under gravity, released 0.5 m sideways from its
/// anchor and spinning slowly; `offset` moves the anchor and the bob.
struct Scene {
  BodyModel body;
  BodyState start;
};

Scene hanging_spring(const Eigen::Vector3d& offset) {
  Scene s;
  s.body.name = "bob";
  s.body.mass = 2.0;
  s.body.moments = Eigen::Vector3d(0.01, 0.02, 0.03);
  s.body.forces = {Gravity{kG}, Spring{offset, Eigen::Vector3d::Zero(), 8.0, 0.0}};
  s.start = spinning_state(s.body, Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.1, 0.2, 0.3));
  s.start.position = offset + Eigen::Vector3d(0.5, 0.0, -1.0);
  return s;
}

/// The heavy top of the stability suite (1 kg, centre of mass 0.5 m up the axis, I about the
/// pivot (1.25, 1.25, 0.5), spin 50 rad/s, tilted 0.3 rad), its pivot at `offset`.
Scene offset_heavy_top(const Eigen::Vector3d& offset) {
  Scene s;
  s.body.name = "top";
  s.body.moments = Eigen::Vector3d(1.25, 1.25, 0.5);
  s.body.pivoted = true;
  s.body.pivot = offset;
  s.body.center_offset = Eigen::Vector3d(0.0, 0.0, 0.5);
  s.body.forces = {Gravity{kG}};
  s.start =
      spinning_state(s.body, Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX())),
                     Eigen::Vector3d(0.0, 0.0, 50.0));
  update_pivot_kinematics(s.body, s.start);
  return s;
}

/// A fast needle (1 : 1000 : 1000) thrown upward at 5 m/s under gravity from `offset`.
Scene falling_needle(const Eigen::Vector3d& offset) {
  Scene s;
  s.body.name = "needle";
  s.body.moments = Eigen::Vector3d(1.0, 1000.0, 1000.0);
  s.body.forces = {Gravity{kG}};
  s.start =
      spinning_state(s.body, Eigen::Quaterniond::Identity(), Eigen::Vector3d(100.0, 0.01, 0.0));
  s.start.position = offset;
  s.start.velocity = Eigen::Vector3d(1.0, 0.0, 5.0);
  return s;
}

TEST(EnergyScale, ASpringIsItsOwnSwingWhereverItIs) {
  for (const double shift : {0.0, 100.0, 1e6}) {
    Scene s = hanging_spring(Eigen::Vector3d(shift, 0.0, 0.0));
    s.body.forces.erase(s.body.forces.begin());  // the spring alone
    // k/2 |P - a|^2 = 4 * 1.25 = 5 J plus the spin, w . J w / 2 = (1e-4 + 8e-4 + 2.7e-3) / 2.
    const double expected = 5.0 + 0.5 * (0.01 * 0.01 + 0.02 * 0.04 + 0.03 * 0.09);
    EXPECT_NEAR(energy_scale(s.body, s.start, 10.0), expected, 1e-15 * (1.0 + shift)) << shift;
    EXPECT_NEAR(energy(s.body, s.start), expected, 1e-9 * (1.0 + shift));  // E0 is that too
  }
}

TEST(EnergyScale, APivotedTopTradesItsDropToTheLowestPoint) {
  for (const double height : {0.0, 100.0, 1e6}) {
    const Scene s = offset_heavy_top(Eigen::Vector3d(0.0, 0.0, height));
    // 625 J of spin plus m g l (1 + cos 0.3); independent of the pivot's height, unlike E0.
    const double expected = 0.5 * 0.5 * 50.0 * 50.0 + 9.81 * 0.5 * (1.0 + std::cos(0.3));
    EXPECT_NEAR(energy_scale(s.body, s.start, 2.0), expected, 1e-12 * expected) << height;
  }
  // Hanging straight down there is nothing to release.
  Scene hanging = offset_heavy_top(Eigen::Vector3d::Zero());
  hanging.start = spinning_state(
      hanging.body, Eigen::Quaterniond(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX())),
      Eigen::Vector3d::Zero());
  EXPECT_NEAR(energy_scale(hanging.body, hanging.start, 2.0), 0.0, 1e-14);
}

TEST(EnergyScale, AFreeFallCountsTheLargestKineticEnergyOfTheExactFall) {
  const Scene s = falling_needle(Eigen::Vector3d(0.0, 0.0, 1e6));
  const double spin = 0.5 * (100.0 * 100.0 + 1000.0 * 1e-4);
  // Over 2 s the fall ends at |(1, 0, 5 - 19.62)| m/s; over 0.5 s it is still slower than at the
  // start, whose 26 m^2/s^2 is the largest.
  EXPECT_NEAR(energy_scale(s.body, s.start, 2.0), spin + 0.5 * (1.0 + 14.62 * 14.62), 1e-9);
  EXPECT_NEAR(energy_scale(s.body, s.start, 0.5), spin + 0.5 * 26.0, 1e-9);
}

TEST(EnergyScale, GravityOnASpringAddsItsSagEnergy) {
  const Scene s = hanging_spring(Eigen::Vector3d(1e6, 0.0, 0.0));
  const double spin = 0.5 * (0.01 * 0.01 + 0.02 * 0.04 + 0.03 * 0.09);
  // m^2 g^2 / k = 4 * 9.81^2 / 8.
  EXPECT_NEAR(energy_scale(s.body, s.start, 1.0), spin + 5.0 + 0.5 * 9.81 * 9.81, 1e-9);
}

/// The blow-up step (or none) of `scene` under `kind`; nullopt when the integrator refuses it.
std::optional<std::size_t> blow_up_step(const Scene& scene, IntegratorKind kind, double dt,
                                        double duration, bool* refused) {
  SimulationSettings settings;
  settings.integrator = kind;
  settings.dt = dt;
  settings.duration = duration;
  *refused = false;
  try {
    Simulation sim({scene.body}, {scene.start}, settings);
    while (sim.step()) {
    }
    if (sim.blow_up()) return sim.blow_up()->step;
    EXPECT_EQ(sim.steps(), sim.total_steps());
    return 0;
  } catch (const InputError&) {
    *refused = true;
    return std::nullopt;
  }
}

/// The same verdict, at the same step, wherever the scene is put; and at least one integrator
/// does blow up at the origin (so the comparison has something to compare).
void expect_same_blow_ups(Scene (*make)(const Eigen::Vector3d&), double dt, double duration) {
  int blew_up = 0;
  for (const IntegratorInfo& info : integrator_catalog()) {
    bool refused = false;
    const std::optional<std::size_t> here =
        blow_up_step(make(Eigen::Vector3d::Zero()), info.kind, dt, duration, &refused);
    if (refused) continue;
    blew_up += *here > 0;
    for (const double distance : {100.0, 1e6}) {
      for (const Eigen::Vector3d& direction :
           {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(1, 0, 0)}) {
        bool moved_refused = false;
        EXPECT_EQ(blow_up_step(make(distance * direction), info.kind, dt, duration, &moved_refused),
                  here)
            << info.name << " moved by " << distance << " m along " << direction.transpose();
      }
    }
  }
  EXPECT_GT(blew_up, 0);
}

TEST(BlowUpRule, ASpringUnderGravityBlowsUpAtTheSameStepWhereverItHangs) {
  // wn dt = 2.1: beyond symplectic Euler's limit; explicit Euler grows by 1 + (wn dt)^2 a step.
  expect_same_blow_ups(hanging_spring, 1.05, 21.0);
}

TEST(BlowUpRule, AHeavyTopBlowsUpAtTheSameStepWhereverItsPivotIs) {
  expect_same_blow_ups(offset_heavy_top, 0.02, 1.0);
}

TEST(BlowUpRule, AFallingNeedleBlowsUpAtTheSameStepWhereverItFalls) {
  expect_same_blow_ups(falling_needle, 0.05, 1.0);
}

}  // namespace
}  // namespace tumble::engine
