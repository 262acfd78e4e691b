// End-to-end tests of `tumble stability` on the quick suite: the outcomes engine/PHYSICS.md §7
// predicts (explicit Euler blows up on the needle where splitting holds, implicit Euler damps
// the fast top, symplectic Euler's limit at wn dt = 2), the outputs and the errors.
#include "app/commands/stability_command.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>

#include "app/analysis/stability_classes.hpp"
#include "support/csv_reader.hpp"
#include "support/run_command.hpp"

namespace tumble::app {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
using tumble::testing::fresh_directory;
using tumble::testing::read_text;
using tumble::testing::run_command;
using tumble::testing::tumble_executable;

/// The CSV as rows of column name -> value (RFC 4180, as tumble writes it).
std::vector<std::map<std::string, std::string>> stability_rows(
    const std::filesystem::path& file, std::vector<std::string>* header = nullptr) {
  testing::CsvTable table = testing::read_csv(file);
  if (header) *header = table.header;
  return table.rows;
}

/// The one row of (case, integrator, rate dt).
std::map<std::string, std::string> find_stability_row(
    const std::vector<std::map<std::string, std::string>>& rows, const std::string& case_name,
    const std::string& integrator, double rate_dt) {
  for (const auto& row : rows) {
    if (row.at("case") == case_name && row.at("integrator") == integrator &&
        std::abs(std::stod(row.at("rate_dt")) - rate_dt) < 1e-9 * rate_dt) {
      return row;
    }
  }
  ADD_FAILURE() << "no row " << case_name << " " << integrator << " " << rate_dt;
  return {};
}

/// One quick-suite run shared by the tests of this file.
class QuickSuite : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    folder_ = new std::filesystem::path(fresh_directory("stability_quick"));
    result_ = new tumble::testing::CommandResult(run_command(
        tumble_executable() + " stability --suite quick -o '" + (*folder_ / "out").string() + "'"));
  }
  static void TearDownTestSuite() {
    std::filesystem::remove_all(*folder_);
    delete folder_;
    delete result_;
  }
  static std::filesystem::path out() { return *folder_ / "out"; }
  static std::filesystem::path* folder_;
  static tumble::testing::CommandResult* result_;
};
std::filesystem::path* QuickSuite::folder_ = nullptr;
tumble::testing::CommandResult* QuickSuite::result_ = nullptr;

TEST_F(QuickSuite, ExitsZeroWithProgressOnStderr) {
  EXPECT_EQ(result_->status, 0) << result_->err;
  EXPECT_THAT(result_->err, HasSubstr("[1/3] needle"));
  EXPECT_THAT(result_->out, HasSubstr("runs over 3 cases"));
  // No temporary of any process is left beside the output (the run was another process).
  const std::string temporary_prefix = "." + out().filename().string() + ".tmp-";
  for (const auto& entry : std::filesystem::directory_iterator(out().parent_path())) {
    EXPECT_FALSE(entry.path().filename().string().starts_with(temporary_prefix)) << entry.path();
  }
}

TEST_F(QuickSuite, ExplicitEulerBlowsUpOnTheNeedleWhereSplittingIsStable) {
  const auto rows = stability_rows(out() / "stability.csv");
  const auto explicit_run = find_stability_row(rows, "needle", "explicit-euler", 5.0);
  EXPECT_EQ(explicit_run.at("outcome"), "blew up");
  EXPECT_FALSE(explicit_run.at("blowup_time").empty());
  EXPECT_GT(std::stod(explicit_run.at("blowup_time")), 0.0);
  const auto splitting = find_stability_row(rows, "needle", "splitting", 5.0);
  EXPECT_EQ(splitting.at("outcome"), "stable");
  EXPECT_LT(std::abs(std::stod(splitting.at("energy_max_gain"))), 1e-3);
  EXPECT_EQ(splitting.at("reference"), "exact");
  EXPECT_FALSE(splitting.at("orientation_error").empty());
}

TEST_F(QuickSuite, ImplicitEulerDampsTheFastTop) {
  const auto rows = stability_rows(out() / "stability.csv");
  for (const double rate_dt : {0.2, 0.5}) {
    const auto run = find_stability_row(rows, "heavy-top", "implicit-euler", rate_dt);
    EXPECT_LT(std::stod(run.at("energy_change_final")), -1e-3);
    EXPECT_EQ(run.at("reference"), "exact top");
  }
  // At w3 dt = 0.2 a persistent loss within 1% of the scale; at 0.5 the damped precession has
  // turned world L by more than 1%: bounded, but wrong.
  EXPECT_EQ(find_stability_row(rows, "heavy-top", "implicit-euler", 0.2).at("outcome"), "damped");
  const auto coarse = find_stability_row(rows, "heavy-top", "implicit-euler", 0.5);
  EXPECT_EQ(coarse.at("outcome"), "wrong");
  EXPECT_GT(std::stod(coarse.at("momentum_error")), 1e-2);
  // The heavy top is a Lagrange top: the exact integrator runs it (engine/PHYSICS.md §4b),
  // keeps its invariants and lands on the reference, which is the same solution.
  const auto exact = find_stability_row(rows, "heavy-top", "exact", 0.2);
  EXPECT_EQ(exact.at("outcome"), "stable");
  EXPECT_LT(std::stod(exact.at("orientation_error")), 1e-12);
}

TEST_F(QuickSuite, SymplecticEulerFlipsAcrossWnDtOfTwoOnTheStiffSpring) {
  const auto rows = stability_rows(out() / "stability.csv");
  // Below the limit the energy swings to 1 / (1 - wn dt / 2) times E0 (4x, 20x) and stays
  // bounded: wrong (energy off by far more than 1%), not blown up.
  for (const double rate_dt : {1.5, 1.9}) {
    const auto run = find_stability_row(rows, "stiff-spring", "semi-implicit-euler", rate_dt);
    EXPECT_EQ(run.at("outcome"), "wrong") << rate_dt;
    EXPECT_GT(std::stod(run.at("energy_max_gain")), 1.0) << rate_dt;
    EXPECT_FALSE(run.at("position_error").empty());
  }
  EXPECT_EQ(find_stability_row(rows, "stiff-spring", "semi-implicit-euler", 2.1).at("outcome"),
            "blew up");
}

TEST_F(QuickSuite, CsvHasEveryColumnAndOneRowPerRun) {
  std::vector<std::string> header;
  const auto rows = stability_rows(out() / "stability.csv", &header);
  for (const char* column : {"suite",
                             "case",
                             "integrator",
                             "dt",
                             "rate_label",
                             "rate_dt",
                             "duration",
                             "steps",
                             "total_steps",
                             "outcome",
                             "blowup_time",
                             "blowup_reason",
                             "energy_change_final",
                             "energy_max_gain",
                             "energy_max_loss",
                             "momentum_change_final",
                             "momentum_max_gain",
                             "momentum_max_loss",
                             "orientation_error",
                             "position_error",
                             "momentum_error",
                             "motion_range",
                             "reference_instants",
                             "reference",
                             "wall_seconds",
                             "note"}) {
    EXPECT_NE(std::find(header.begin(), header.end(), column), header.end()) << column;
  }
  // 13 integrators x (2 + 2 + 3) dts.
  EXPECT_EQ(rows.size(), 13u * 7u);
  for (const auto& row : rows) EXPECT_EQ(row.at("suite"), "quick");
}

TEST_F(QuickSuite, MarkdownHasTheRulesAndOneMatrixPerCase) {
  const std::string md = read_text(out() / "stability.md");
  EXPECT_THAT(md, HasSubstr("## Classification rules"));
  EXPECT_THAT(md, HasSubstr("**damped**"));
  for (const char* name : {"needle", "heavy-top", "stiff-spring"}) {
    EXPECT_THAT(md, HasSubstr(std::string("## Case `") + name + "`"));
  }
  EXPECT_THAT(md, HasSubstr("| integrator | 0.5 | 5 |"));
  EXPECT_THAT(md, HasSubstr("| integrator | 1.5 | 1.9 | 2.1 |"));
}

TEST_F(QuickSuite, HeatMapPngAndSvgAreValid) {
  const std::string png = read_text(out() / "stability.png");
  ASSERT_GE(png.size(), 8u);
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  const std::string svg = read_text(out() / "stability.svg");
  EXPECT_THAT(svg, HasSubstr("<svg"));
  EXPECT_THAT(svg, HasSubstr("blew up"));
  // The temporary gnuplot script is gone.
  EXPECT_FALSE(std::filesystem::exists(out() / ".stability.gp"));
}

// ---------------------------------------------------------------------------------------------

TEST(StabilityClassify, AppliesTheRulesToSignedChanges) {
  // Changes within the 1% of the scale beyond which a run is wrong (engine/PHYSICS.md §7).
  InvariantChanges c;
  c.energy_applies = true;
  EXPECT_EQ(classify(true, c, 1e-3), StabilityOutcome::kBlewUp);
  EXPECT_EQ(classify(false, c, 1e-3), StabilityOutcome::kStable);
  c.energy_final = -0.005;
  c.energy_max_loss = 0.005;
  c.energy_late_max = -0.004;
  c.energy_late_min = -0.005;
  EXPECT_EQ(classify(false, c, 1e-3), StabilityOutcome::kDamped);
  c.energy_max_gain = 0.002;  // it also grew: not a plain loss
  EXPECT_EQ(classify(false, c, 1e-3), StabilityOutcome::kDrifting);
  c.energy_max_gain = 0.0;
  c.energy_late_max = 0.0;  // a loss that swings back to E0: not damping
  EXPECT_EQ(classify(false, c, 1e-3), StabilityOutcome::kDrifting);
  c.energy_late_max = -0.004;  // a wide bounded swing below E0: not damping
  c.energy_late_min = -0.009;
  c.energy_max_loss = 0.009;
  EXPECT_EQ(classify(false, c, 1e-3), StabilityOutcome::kDrifting);
  c.energy_max_loss = 0.02;  // beyond 1%: bounded, but wrong
  EXPECT_EQ(classify(false, c, 1e-3), StabilityOutcome::kWrong);
  c = {};
  c.energy_applies = true;
  c.energy_final = 0.002;
  c.energy_max_gain = 0.002;
  EXPECT_EQ(classify(false, c, 1e-3), StabilityOutcome::kDrifting);
  c = {};
  EXPECT_EQ(classify(false, c, 1e-3), StabilityOutcome::kUnchecked);
}

TEST(StabilityCommand, UserSceneAppearsAsACase) {
  const auto dir = fresh_directory("stability_scene");
  const auto scene = dir / "wobbly.json";
  std::ofstream(scene) << R"({"name": "wobbly", "duration": 2, "dt": 0.01,
    "bodies": [{"inertia": {"principal": [1, 2, 3]}, "mass": 1,
                "angular_velocity": [0.4, 0.8, 0.6]}]})";
  const auto out = dir / "out";
  const auto result = run_command(tumble_executable() + " stability --integrators splitting,rk4 '" +
                                  scene.string() + "' -o '" + out.string() + "'");
  ASSERT_EQ(result.status, 0) << result.err;
  const auto rows = stability_rows(out / "stability.csv");
  ASSERT_EQ(rows.size(), 2u * 4u);  // dt x {1, 2, 4, 8}
  for (const auto& row : rows) {
    EXPECT_EQ(row.at("case"), "wobbly");
    EXPECT_EQ(row.at("outcome"), "stable") << row.at("integrator") << " " << row.at("dt");
  }
  EXPECT_EQ(find_stability_row(rows, "wobbly", "rk4", 0.08).at("reference"), "exact");
  EXPECT_THAT(read_text(out / "stability.md"), HasSubstr("## Case `wobbly`"));

  // With --dts the sweep is the user's.
  const auto again =
      run_command(tumble_executable() + " stability --integrators rk4 --dts 0.05,0.1 '" +
                  scene.string() + "' -o '" + out.string() + "'");
  ASSERT_EQ(again.status, 0) << again.err;
  EXPECT_EQ(stability_rows(out / "stability.csv").size(), 2u);
  std::filesystem::remove_all(dir);
}

// Three scenes: a free tumbling body, a body driven by a constant torque and a bob on a damped
// spring. seed-semi-implicit keeps energy and |L| of the free body to rounding (engine/PHYSICS.md
// §2) but turns it about the wrong axis: `wrong`, not `stable`. The forced scenes are judged
// against their dopri reference (energy compared with the reference's at shared instants), not
// left `unchecked`. Every cell carries its error against the reference.
TEST(StabilityCommand, FreeAndForcedScenesAreJudgedAgainstTheirReference) {
  const auto dir = fresh_directory("stability_forced");
  std::ofstream(dir / "free.json") << R"({"name": "free", "duration": 2, "dt": 0.01,
    "bodies": [{"inertia": {"principal": [1, 2, 3]}, "mass": 1,
                "angular_velocity": [0.4, 0.8, 0.6]}]})";
  std::ofstream(dir / "pushed.json") << R"({"name": "pushed", "duration": 2, "dt": 0.01,
    "bodies": [{"inertia": {"principal": [1, 2, 3]}, "mass": 1,
                "angular_velocity": [0, 1, 0], "torque": [0, 0, 0.5]}]})";
  std::ofstream(dir / "damped.json") << R"({"name": "damped", "duration": 4, "dt": 0.01,
    "bodies": [{"inertia": {"principal": [0.01, 0.01, 0.01]}, "mass": 2, "position": [0.5, 0, 0],
                "spring": {"anchor": [0, 0, 0], "attach": [0, 0, 0], "stiffness": 8,
                           "damping": 0.4}}]})";
  const auto out = dir / "out";
  const auto result = run_command(
      tumble_executable() + " stability --integrators seed-semi-implicit,rk4,explicit-euler '" +
      (dir / "free.json").string() + "' '" + (dir / "pushed.json").string() + "' '" +
      (dir / "damped.json").string() + "' -o '" + out.string() + "'");
  ASSERT_EQ(result.status, 0) << result.err;
  const auto rows = stability_rows(out / "stability.csv");
  ASSERT_EQ(rows.size(), 3u * 3u * 4u);

  // The free body: seed-semi-implicit keeps the invariants and is wrong; rk4 is stable.
  for (const double dt : {0.01, 0.08}) {
    const auto seed = find_stability_row(rows, "free", "seed-semi-implicit", dt);
    EXPECT_EQ(seed.at("outcome"), "wrong") << dt;
    EXPECT_LT(std::stod(seed.at("energy_max_gain")), 1e-9) << dt;
    EXPECT_GT(std::stod(seed.at("orientation_error")), 0.1) << dt;
    EXPECT_EQ(find_stability_row(rows, "free", "rk4", dt).at("outcome"), "stable") << dt;
  }
  // The forced bodies: classified against dopri, every shared instant compared (scene steps
  // dt x {1, 2, 4, 8} all land on the reference's samples).
  for (const char* name : {"pushed", "damped"}) {
    for (const double dt : {0.01, 0.02, 0.04, 0.08}) {
      const auto rk4 = find_stability_row(rows, name, "rk4", dt);
      EXPECT_EQ(rk4.at("outcome"), "stable") << name << " " << dt;
      EXPECT_EQ(rk4.at("reference"), "dopri 1e-13");
      EXPECT_FALSE(rk4.at("energy_max_gain").empty());
      // Sampled every 0.08 s (the largest step, >= duration / 100): 25 or 50 instants.
      EXPECT_EQ(std::stoi(rk4.at("reference_instants")), std::string(name) == "pushed" ? 25 : 50)
          << name << " " << dt;
      EXPECT_LT(std::stod(rk4.at("orientation_error")), 1e-3);
    }
    for (const auto& row : rows) EXPECT_NE(row.at("outcome"), "unchecked") << row.at("case");
  }
  // Explicit Euler on the damped spring at wn dt = 0.16: energy off the reference's by more
  // than 1% of the scale, shown as wrong with its position error.
  const auto euler = find_stability_row(rows, "damped", "explicit-euler", 0.08);
  EXPECT_EQ(euler.at("outcome"), "wrong");
  EXPECT_GT(std::stod(euler.at("position_error")), 1e-3);

  // The matrix cells carry the errors: radians everywhere, metres where positions move.
  const std::string md = read_text(out / "stability.md");
  EXPECT_THAT(md, HasSubstr("**wrong**"));
  EXPECT_THAT(md, ::testing::ContainsRegex("\\| wrong( \\([-+][0-9.e+-]+\\))?, [0-9.e+-]+ rad"));
  EXPECT_THAT(md, ::testing::ContainsRegex("\\| stable, [0-9.e+-]+ rad, [0-9.e+-]+ m \\|"));
  std::filesystem::remove_all(dir);
}

TEST(StabilityCommand, ReplacesOnlyAnEmptyFolderOrAnEarlierOutput) {
  const auto dir = fresh_directory("stability_output");
  const auto scene = dir / "wobbly.json";
  std::ofstream(scene) << R"({"name": "wobbly", "duration": 1, "dt": 0.01,
    "bodies": [{"inertia": {"principal": [1, 2, 3]}, "mass": 1,
                "angular_velocity": [0.4, 0.8, 0.6]}]})";
  const auto stability = [&](const std::filesystem::path& out) {
    return run_command(tumble_executable() + " stability --integrators rk4 --dts 0.1 '" +
                       scene.string() + "' -o '" + out.string() + "'");
  };
  // A new folder, then the same one again: an earlier output is replaced.
  ASSERT_EQ(stability(dir / "out").status, 0);
  const auto again = stability(dir / "out");
  EXPECT_EQ(again.status, 0) << again.err;
  EXPECT_EQ(stability_rows(dir / "out" / "stability.csv").size(), 1u);
  // An empty folder is used.
  std::filesystem::create_directory(dir / "empty");
  EXPECT_EQ(stability(dir / "empty").status, 0);
  EXPECT_TRUE(std::filesystem::exists(dir / "empty" / "stability.md"));
  // A folder holding anything else is left alone.
  std::filesystem::create_directory(dir / "mine");
  std::ofstream(dir / "mine" / "notes.txt") << "keep";
  const auto refused = stability(dir / "mine");
  EXPECT_EQ(refused.status, 1);
  EXPECT_THAT(refused.err,
              HasSubstr("-o: " + (dir / "mine").string() +
                        " exists and is neither empty nor a previous stability output"));
  EXPECT_EQ(read_text(dir / "mine" / "notes.txt"), "keep");
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir / "mine"),
                          std::filesystem::directory_iterator()),
            1);
  // No temporaries left behind.
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    EXPECT_EQ(name.find(".tmp"), std::string::npos) << name;
    EXPECT_EQ(name.find(".old"), std::string::npos) << name;
  }
  std::filesystem::remove_all(dir);
}

TEST(StabilityCommand, ListSuitesNamesTheSuites) {
  const auto result = run_command(tumble_executable() + " stability --list-suites");
  EXPECT_EQ(result.status, 0);
  EXPECT_THAT(result.out, HasSubstr("standard"));
  EXPECT_THAT(result.out, HasSubstr("quick"));
  EXPECT_THAT(result.out, HasSubstr("stiff-spring"));
}

/// Runs a failing command; checks exit 1, one line naming the problem, no output folder.
void expect_input_error(const std::string& arguments, const std::string& message) {
  const auto dir = fresh_directory("stability_errors");
  const auto result = run_command(tumble_executable() + " stability " + arguments);
  EXPECT_EQ(result.status, 1) << arguments;
  EXPECT_THAT(result.err, HasSubstr(message)) << arguments;
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  std::filesystem::remove_all(dir);
}

TEST(StabilityCommand, InputErrorsAreOneLineAndExitOne) {
  const std::string out = (std::filesystem::temp_directory_path() / "tumble_stab_err").string();
  expect_input_error("--suite nope -o " + out, "--suite: unknown suite 'nope'");
  expect_input_error("--suite quick --integrators rk4,warp -o " + out,
                     "--integrators: unknown integrator 'warp'");
  expect_input_error("--suite quick --dts 0.1,abc -o " + out,
                     "--dts: expected a positive number, got 'abc'");
  expect_input_error("--suite quick --dts=-1 -o " + out, "--dts");
  expect_input_error("--suite quick --cases needle,nope -o " + out, "--cases: no case 'nope'");
  expect_input_error("--suite quick -o /nonexistent/folder/out",
                     "-o: cannot create /nonexistent/folder/out");
  expect_input_error("--suite quick", "-o DIR is required");
  EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace tumble::app
