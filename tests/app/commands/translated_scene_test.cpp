// Verdicts that do not depend on where zero is (engine/PHYSICS.md §6, §7): the same scene moved
// by 100 m and by 10^6 m, along gravity and across it, gives the same exit code of `tumble
// simulate`, the same blow-up step and time, and the same stability class under every integrator.
// Three scenes: a spring under gravity that blows up, a pivoted heavy top, a free needle falling.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "app/analysis/stability_runner.hpp"
#include "app/analysis/stability_suite.hpp"
#include "app/commands/simulate_command.hpp"
#include "app/support/exit_status.hpp"
#include "engine/dynamics/integrators.hpp"
#include "support/run_command.hpp"
#include "support/scene_builder.hpp"

namespace tumble::app {
namespace {

using nlohmann::json;
using testing::BodyBuilder;
using testing::SceneBuilder;

const Eigen::Vector3d kGravity(0.0, 0.0, -9.81);

/// A 2 kg bob on an 8 N/m spring (wn = 2 rad/s) under gravity, at wn dt = 2.1: beyond the limit
/// of symplectic Euler.
json spring_scene(const Eigen::Vector3d& offset) {
  const Eigen::Vector3d anchor = offset;
  return SceneBuilder()
      .name("spring")
      .duration(8.4)
      .dt(1.05)
      .set("gravity", {kGravity.x(), kGravity.y(), kGravity.z()})
      .body(BodyBuilder("bob")
                .principal({0.01, 0.02, 0.03})
                .mass(2.0)
                .position(offset + Eigen::Vector3d(0.5, 0.0, -1.0))
                .angular_velocity({0.1, 0.2, 0.3}, "body")
                .set("spring", {{"anchor", {anchor.x(), anchor.y(), anchor.z()}},
                                {"attach", {0, 0, 0}},
                                {"stiffness", 8.0}}))
      .json();
}

/// A heavy symmetric top, its pivot 0.5 m below the centre of mass, spinning at 50 rad/s.
json top_scene(const Eigen::Vector3d& offset) {
  return SceneBuilder()
      .name("top")
      .duration(2.0)
      .dt(0.02)
      .set("gravity", {kGravity.x(), kGravity.y(), kGravity.z()})
      .body(BodyBuilder("top")
                .principal({1, 1, 0.5})
                .mass(1.0)
                .position(offset)
                .set("pivot", {0, 0, -0.5})
                .orientation(std::cos(0.15), std::sin(0.15), 0, 0)
                .angular_velocity({0, 0, 50}, "body"))
      .json();
}

/// A needle (1 : 1000 : 1000) thrown upward at 5 m/s while spinning fast about its axis.
json falling_scene(const Eigen::Vector3d& offset) {
  return SceneBuilder()
      .name("falling")
      .duration(1.0)
      .dt(0.05)
      .set("gravity", {kGravity.x(), kGravity.y(), kGravity.z()})
      .body(BodyBuilder("needle")
                .principal({0.001, 1, 1})
                .mass(1.0)
                .position(offset)
                .velocity({1, 0, 5})
                .angular_velocity({100.0, 0.01, 0.0}, "body"))
      .json();
}

/// `tumble simulate` in process: the exit code and where it blew up ("" when it did not).
struct Verdict {
  int status = 0;
  std::string where;
};

Verdict simulate(const std::filesystem::path& scene, const std::string& integrator) {
  SimulateOptions options;
  options.scene = scene;
  options.integrator = integrator;
  std::ostringstream out, err;
  Verdict v;
  v.status = run_simulate(options, out, err);
  // "... body 'bob' at step 3 (t = 3.15 s): <reason>": up to the reason.
  const std::string text = err.str();
  const std::size_t at = text.find(" at step ");
  if (at != std::string::npos) v.where = text.substr(at, text.find("):", at) - at);
  return v;
}

/// Every integrator on `make(offset)` for the offsets, against the scene at the origin.
void expect_same_verdicts(json (*make)(const Eigen::Vector3d&), const std::string& name) {
  const auto dir = testing::fresh_directory("translated_" + name);
  std::vector<std::filesystem::path> files;
  std::vector<Eigen::Vector3d> offsets = {Eigen::Vector3d::Zero()};
  for (const double distance : {100.0, 1e6}) {
    offsets.push_back(Eigen::Vector3d(0, 0, distance));  // along gravity
    offsets.push_back(Eigen::Vector3d(distance, 0, 0));  // across it
  }
  std::vector<StabilityCase> cases;
  std::vector<StabilityReference> references;
  for (std::size_t k = 0; k < offsets.size(); ++k) {
    const auto file = dir / (name + std::to_string(k) + ".json");
    std::ofstream(file) << make(offsets[k]).dump(2);
    files.push_back(file);
    cases.push_back(scene_case(file, std::nullopt));
    references.push_back(stability_reference(cases.back()));
  }
  int blew_up = 0;
  std::string statuses;
  for (const engine::IntegratorInfo& info : engine::integrator_catalog()) {
    const Verdict here = simulate(files[0], info.name);
    blew_up += here.status == kExitBlowUp;
    statuses += " " + info.name + ":" + std::to_string(here.status);
    std::vector<StabilityRun> runs;
    for (const double dt : cases[0].dts) {
      runs.push_back(run_stability_case(cases[0], info, dt, references[0]));
    }
    for (std::size_t k = 1; k < offsets.size(); ++k) {
      const std::string moved = info.name + " moved by " + std::to_string(offsets[k].norm()) +
                                " m along " + (offsets[k].z() != 0 ? "gravity" : "x");
      const Verdict there = simulate(files[k], info.name);
      EXPECT_EQ(there.status, here.status) << moved;
      EXPECT_EQ(there.where, here.where) << moved;
      for (std::size_t d = 0; d < cases[k].dts.size(); ++d) {
        const StabilityRun run = run_stability_case(cases[k], info, cases[k].dts[d], references[k]);
        EXPECT_EQ(outcome_name(run.outcome), std::string(outcome_name(runs[d].outcome)))
            << moved << " dt " << cases[k].dts[d];
        EXPECT_EQ(run.blowup_reason.substr(0, run.blowup_reason.find(':')),
                  runs[d].blowup_reason.substr(0, runs[d].blowup_reason.find(':')))
            << moved;
      }
    }
  }
  EXPECT_GT(blew_up, 0) << name << ": nothing blew up, nothing was compared;" << statuses;
  std::filesystem::remove_all(dir);
}

TEST(TranslatedScene, ASpringUnderGravityHasTheSameVerdictsWhereverItHangs) {
  expect_same_verdicts(spring_scene, "spring");
}

TEST(TranslatedScene, AHeavyTopHasTheSameVerdictsWhereverItsPivotIs) {
  expect_same_verdicts(top_scene, "top");
}

TEST(TranslatedScene, AFallingBodyHasTheSameVerdictsWhereverItFalls) {
  expect_same_verdicts(falling_scene, "falling");
}

}  // namespace
}  // namespace tumble::app
