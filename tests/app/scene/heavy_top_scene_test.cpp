// The heavy-top scene (assets/scenes/heavy_top.json, a mesh top) is a Lagrange top to the
// tolerance of engine/PHYSICS.md §4b, so its reference is the exact solution; checked here
// against dopri at 1e-13.
#include <gtest/gtest.h>

#include <filesystem>
#include <limits>
#include <vector>

#include "app/scene/scene.hpp"
#include "engine/exact/lagrange_top.hpp"
#include "engine/simulation/reference_motion.hpp"
#include "engine/simulation/simulation.hpp"

namespace tumble::app {
namespace {

TEST(HeavyTopScene, ItsReferenceIsTheExactTopAndAgreesWithDopri) {
  const std::filesystem::path file =
      std::filesystem::path(TUMBLE_SOURCE_DIR) / "assets/scenes/heavy_top.json";
  const CompiledScene compiled = compile_scene(load_scene(file));
  ASSERT_EQ(compiled.bodies.size(), 1u);
  ASSERT_TRUE(engine::is_lagrange_top(compiled.bodies[0]))
      << engine::lagrange_top_problem(compiled.bodies[0]).value_or("");
  const engine::ReferenceMotion reference(compiled.bodies, compiled.initial);
  EXPECT_EQ(reference.kind(), engine::ReferenceMotion::Kind::kExactWithTops);

  engine::SimulationSettings settings;
  settings.integrator = engine::IntegratorKind::kDopri;
  settings.dt = 0.05;
  settings.duration = 1.0;
  settings.tolerance = 1e-13;
  settings.blowup_factor = std::numeric_limits<double>::infinity();
  engine::Simulation dopri(compiled.bodies, compiled.initial, settings);
  const std::vector<std::vector<engine::BodyState>> exact = reference.sample(0.05, 1.0);
  double worst = 0.0, worst_momentum = 0.0;
  for (std::size_t k = 0; dopri.step(); ++k) {
    const engine::BodyState& ode = dopri.states()[0];
    worst = std::max(worst, engine::orientation_angle(ode.orientation, exact[k][0].orientation));
    worst_momentum =
        std::max(worst_momentum, (ode.angular_momentum - exact[k][0].angular_momentum).norm() /
                                     ode.angular_momentum.norm());
  }
  EXPECT_EQ(dopri.steps(), exact.size());
  EXPECT_LT(worst, 1e-10);
  EXPECT_LT(worst_momentum, 1e-10);
}

}  // namespace
}  // namespace tumble::app
