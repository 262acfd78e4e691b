// stability's outputs in process (app/analysis/stability_report.hpp): a hand-built matrix of
// outcomes (two integrators by two steps, one cell of each kind) in, the exact CSV rows,
// markdown matrix and heat map cells out.
#include "app/analysis/stability_report.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace tumble::app {
namespace {

using ::testing::HasSubstr;

/// One case, "spin": no rate (columns are dt in s), steps 0.01 and 0.02 s, 2 s long.
StabilityCase spin_case() {
  StabilityCase c;
  c.name = "spin";
  c.description = "A brick spun about its middle axis";
  c.duration = 2.0;
  c.dts = {0.01, 0.02};
  return c;
}

StabilityRun spin_run(const std::string& integrator, double dt, StabilityOutcome outcome) {
  StabilityRun r;
  r.case_name = "spin";
  r.integrator = integrator;
  r.dt = dt;
  r.rate_dt = dt;
  r.duration = 2.0;
  r.total_steps = static_cast<std::size_t>(2.0 / dt + 0.5);
  r.steps = r.total_steps;
  r.outcome = outcome;
  r.reference = "exact";
  r.reference_instants = 101;
  r.changes.energy_applies = true;
  r.changes.momentum_applies = true;
  return r;
}

/// The matrix, in the sweep's order (integrator by integrator, dt by dt):
///            0.01                        0.02
/// rk4        stable, 1.0e-07 rad         drifting (+1.2e-02), 3.0e-03 rad
/// euler      wrong (-4.1e-02), 2.0e-01   blew up (t = 1.37 s)
std::vector<StabilityRun> spin_runs() {
  StabilityRun stable = spin_run("rk4", 0.01, StabilityOutcome::kStable);
  stable.orientation_error = 1e-7;
  stable.changes.energy_max_gain = 2e-8;
  StabilityRun drifting = spin_run("rk4", 0.02, StabilityOutcome::kDrifting);
  drifting.orientation_error = 3e-3;
  drifting.changes.energy_max_gain = 0.012;  // beats the |L| gain below: the cell shows it
  drifting.changes.momentum_max_gain = 0.005;
  StabilityRun wrong = spin_run("euler", 0.01, StabilityOutcome::kWrong);
  wrong.orientation_error = 0.2;
  wrong.changes.energy_max_loss = 0.041;  // a loss shows negative
  StabilityRun blew = spin_run("euler", 0.02, StabilityOutcome::kBlewUp);
  blew.steps = 68;
  blew.blowup_time = 1.37;
  blew.blowup_reason = "non-finite state";
  return {stable, drifting, wrong, blew};
}

std::vector<engine::IntegratorInfo> spin_integrators() {
  return {engine::integrator_info(engine::IntegratorKind::kRk4),
          engine::integrator_info(engine::IntegratorKind::kExplicitEuler)};
}

TEST(StabilityReport, TheMarkdownMatrixHasOneCellPerRunInTheSweepsOrder) {
  std::vector<engine::IntegratorInfo> integrators = spin_integrators();
  integrators[1].name = "euler";  // the name the rows show is the integrator's
  const std::string md = stability_markdown("mine", {spin_case()}, integrators, spin_runs());
  EXPECT_THAT(md, ::testing::StartsWith("# tumble stability: suite `mine`\n\n"
                                        "## Classification rules\n\n"));
  EXPECT_THAT(md, HasSubstr("## Case `spin`\n\nA brick spun about its middle axis. Duration 2 s; "
                            "columns are dt in s.\n\n"
                            "| integrator | 0.01 | 0.02 |\n|---|---|---|\n"
                            "| rk4 | stable, 1.0e-07 rad | drifting (+1.2e-02), 3.0e-03 rad |\n"
                            "| euler | wrong (-4.1e-02), 2.0e-01 rad | blew up (t = 1.37 s) |\n"
                            "\nError reference: exact.\n\n"));
  EXPECT_THAT(md, ::testing::EndsWith(
                      "Heat map: `stability.png`, `stability.svg`. Every run: `stability.csv`.\n"));
}

TEST(StabilityReport, TheCsvHasOneRowPerRunWithItsInvariantsAndErrors) {
  const std::string csv = stability_csv("mine", {spin_case()}, spin_runs());
  std::vector<std::string> lines;
  for (std::size_t begin = 0, end; (end = csv.find('\n', begin)) != std::string::npos;
       begin = end + 1) {
    lines.push_back(csv.substr(begin, end - begin));
  }
  ASSERT_EQ(lines.size(), 5u);
  EXPECT_THAT(lines[0], ::testing::StartsWith("suite,case,integrator,dt,rate_label,"));
  EXPECT_EQ(lines[1],
            "mine,spin,rk4,0.01,dt,0.01,2,200,200,stable,,,0.000000e+00,2.000000e-08,"
            "0.000000e+00,0.000000e+00,0.000000e+00,0.000000e+00,1.000000e-07,,,,101,exact,0,");
  EXPECT_EQ(lines[4],
            "mine,spin,euler,0.02,dt,0.02,2,68,100,blew up,1.370000e+00,non-finite state,"
            "0.000000e+00,0.000000e+00,0.000000e+00,0.000000e+00,0.000000e+00,0.000000e+00,,,,,"
            "101,exact,0,");
}

TEST(StabilityReport, TheHeatMapHasTheMarkdownsRowsColumnsAndOutcomes) {
  const std::vector<HeatMapPanel> panels =
      stability_heat_map({spin_case()}, spin_integrators(), spin_runs());
  ASSERT_EQ(panels.size(), 1u);
  EXPECT_EQ(panels[0].title, "spin");
  EXPECT_EQ(panels[0].x_label, "dt (s)");
  EXPECT_EQ(panels[0].columns, (std::vector<std::string>{"0.01", "0.02"}));
  EXPECT_EQ(panels[0].rows, (std::vector<std::string>{"rk4", "explicit-euler"}));
  using O = StabilityOutcome;
  EXPECT_EQ(panels[0].cells,
            (std::vector<std::vector<O>>{{O::kStable, O::kDrifting}, {O::kWrong, O::kBlewUp}}));
}

}  // namespace
}  // namespace tumble::app
