// End-to-end tests of `tumble bench`: orders measured against the exact torque-free solution,
// the CSV, the plots, the report, parallel runs and the errors.
#include "app/commands/bench_command.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "engine/dynamics/integrators.hpp"
#include "support/csv_reader.hpp"
#include "support/run_command.hpp"
#include "support/scene_builder.hpp"

namespace tumble::app {
namespace {

using ::testing::HasSubstr;
using tumble::testing::fresh_directory;
using tumble::testing::read_text;
using tumble::testing::run_command;
using tumble::testing::tumble_executable;

using Csv = testing::CsvTable;
using testing::read_csv;

/// An asymmetric torque-free body, I = (1, 2, 3), w_body = (0.4, 0.8, 0.6).
nlohmann::json torque_free_scene() {
  return testing::SceneBuilder()
      .name("brick")
      .duration(4.0)
      .dt(0.01)
      .body(testing::BodyBuilder("brick").mass(1.0).angular_velocity({0.4, 0.8, 0.6}, "body"))
      .json();
}

/// The integrators under test with their nominal orders (dopri swept by tolerance apart).
const std::map<std::string, double> kOrders = {
    {"explicit-euler", 1}, {"semi-implicit-euler", 1}, {"lie-euler", 1}, {"implicit-euler", 1},
    {"midpoint", 2},       {"splitting", 2},           {"rk4", 4},       {"splitting4", 4},
    {"moser-veselov", 2},  {"seed-semi-implicit", 0}};

class BenchCommand : public ::testing::Test {
 protected:
  /// One full bench shared by the tests that only read its output.
  static void SetUpTestSuite() {
    dir_ = fresh_directory("bench");
    std::ofstream(dir_ / "brick.json") << torque_free_scene().dump(2);
    result_ = run_command(tumble_executable() + " bench '" + (dir_ / "brick.json").string() +
                          "' --tolerances 1e-5,1e-7,1e-9 --repeat 1 -o '" +
                          (dir_ / "out").string() + "'");
  }
  static void TearDownTestSuite() { std::filesystem::remove_all(dir_); }

  static testing::CommandResult bench(const std::string& arguments) {
    return run_command(tumble_executable() + " bench " + arguments);
  }
  static std::string scene() { return "'" + (dir_ / "brick.json").string() + "'"; }
  static std::filesystem::path out() { return dir_ / "out"; }

  /// The observed order the report gives for `name`.
  static std::optional<double> reported_order(const std::string& name) {
    const std::string report = read_text(out() / "report.md");
    const auto section = report.find("### Observed order");
    const auto start = report.find("\n| " + name + " |", section);
    if (section == std::string::npos || start == std::string::npos) return std::nullopt;
    const std::string line = report.substr(start + 1, report.find('\n', start + 1) - start - 1);
    std::vector<std::string> cells;
    std::stringstream in(line);
    std::string cell;
    while (std::getline(in, cell, '|')) cells.push_back(cell);
    // "", " name ", " nominal ", " observed ", ...
    if (cells.size() < 4) return std::nullopt;
    char* end = nullptr;
    const double value = std::strtod(cells[3].c_str(), &end);
    if (end == cells[3].c_str()) return std::nullopt;
    return value;
  }

  static inline std::filesystem::path dir_;
  static inline testing::CommandResult result_;
};

TEST_F(BenchCommand, RunsAndSaysWhereTheReportIs) {
  ASSERT_EQ(result_.status, 0) << result_.err;
  EXPECT_THAT(result_.out, HasSubstr("report.md"));
  // Progress: a line per run when stderr is not a terminal.
  EXPECT_THAT(result_.err, HasSubstr("[1/58]"));
  EXPECT_THAT(result_.err, HasSubstr("[58/58]"));
}

TEST_F(BenchCommand, MeasuredOrdersMatchTheIntegrators) {
  ASSERT_EQ(result_.status, 0) << result_.err;
  for (const auto& [name, order] : kOrders) {
    const auto observed = reported_order(name);
    ASSERT_TRUE(observed.has_value()) << name;
    EXPECT_NEAR(*observed, order, 0.3) << name;
  }
  // free-rotor is exact without torques: every run at the rounding floor, no order to fit.
  EXPECT_FALSE(reported_order("free-rotor").has_value());
  EXPECT_THAT(read_text(out() / "report.md"), HasSubstr("| free-rotor | 2 | n/a (rounding) |"));
  // dopri's error follows its tolerance (one decade per decade, roughly).
  const auto dopri = reported_order("dopri");
  ASSERT_TRUE(dopri.has_value());
  EXPECT_GT(*dopri, 0.6);
  EXPECT_LT(*dopri, 1.3);
}

TEST_F(BenchCommand, CsvHasEveryColumnAndOneRowPerRun) {
  ASSERT_EQ(result_.status, 0) << result_.err;
  const Csv csv = read_csv(out() / "results.csv");
  EXPECT_EQ(csv.header, (std::vector<std::string>{"scene",
                                                  "scene_file",
                                                  "integrator",
                                                  "order",
                                                  "adaptive",
                                                  "dt",
                                                  "tolerance",
                                                  "duration",
                                                  "steps",
                                                  "total_steps",
                                                  "accepted_steps",
                                                  "rejected_steps",
                                                  "evaluations",
                                                  "blew_up",
                                                  "blow_up_time",
                                                  "blow_up_reason",
                                                  "repeats",
                                                  "seconds_median",
                                                  "seconds_min",
                                                  "seconds_max",
                                                  "ns_per_step",
                                                  "core",
                                                  "samples",
                                                  "orientation_error_final",
                                                  "orientation_error_max",
                                                  "omega_error_final",
                                                  "omega_error_max",
                                                  "momentum_error_final",
                                                  "momentum_error_max",
                                                  "energy_drift_max",
                                                  "momentum_norm_drift_max"}));
  // Eleven fixed-step integrators at five steps, dopri at three tolerances.
  ASSERT_EQ(csv.rows.size(), 11u * 5u + 3u);
  std::set<std::string> dts;
  std::map<std::string, int> runs;
  for (const auto& row : csv.rows) {
    ++runs[row.at("integrator")];
    EXPECT_EQ(row.at("blew_up"), "0");
    // Every 0.04 s over 4 s, dopri too (dense output: the same instants for every run).
    EXPECT_EQ(row.at("samples"), "100");
    if (row.at("integrator") != "dopri") dts.insert(row.at("dt"));
    EXPECT_EQ(row.at("repeats"), "1");
    EXPECT_GT(std::stod(row.at("seconds_median")), 0.0);
    EXPECT_LE(std::stod(row.at("orientation_error_final")),
              std::stod(row.at("orientation_error_max")));
  }
  for (const auto& [name, order] : kOrders) EXPECT_EQ(runs[name], 5) << name;
  EXPECT_EQ(runs["free-rotor"], 5);
  EXPECT_EQ(runs["dopri"], 3);
  EXPECT_EQ(dts.size(), 5u);  // 0.01 times 4, 2, 1, 1/2, 1/4
  EXPECT_EQ(runs.count("exact"), 0u);
}

TEST_F(BenchCommand, CountsAndTimingSpreadAreConsistent) {
  ASSERT_EQ(result_.status, 0) << result_.err;
  const Csv csv = read_csv(out() / "results.csv");
  std::map<std::string, int> per_step;
  for (const auto& info : engine::integrator_catalog())
    per_step[info.name] = info.evaluations_per_step;
  std::vector<unsigned long long> dopri_accepted;  // tolerances 1e-5, 1e-7, 1e-9
  for (const auto& row : csv.rows) {
    const std::string& name = row.at("integrator");
    SCOPED_TRACE(name + " dt " + row.at("dt") + " tol " + row.at("tolerance"));
    const auto steps = std::stoull(row.at("steps"));
    const auto accepted = std::stoull(row.at("accepted_steps"));
    const auto rejected = std::stoull(row.at("rejected_steps"));
    const auto evaluations = std::stoull(row.at("evaluations"));
    if (name == "dopri") {
      // First same as last: six evaluations per attempt, one to start (one body), and one per
      // accepted step whose orientation was projected back onto the energy (torque-free).
      EXPECT_GE(evaluations, 6 * (accepted + rejected) + 1);
      EXPECT_LE(evaluations, 7 * accepted + 6 * rejected + 1);
      dopri_accepted.push_back(accepted);
    } else {
      EXPECT_EQ(steps,
                400u / 4u * static_cast<unsigned>(std::lround(0.04 / std::stod(row.at("dt")))));
      EXPECT_EQ(accepted, steps);  // one body
      EXPECT_EQ(rejected, 0u);
      if (name == "midpoint") {
        // One per Newton iteration, counted by the stepper: at least the catalog's two a step.
        EXPECT_GE(evaluations, static_cast<unsigned long long>(per_step.at(name)) * steps);
        EXPECT_LE(evaluations, 50u * steps);
      } else {
        EXPECT_EQ(evaluations, static_cast<unsigned long long>(per_step.at(name)) * steps);
      }
    }
    // rk4 by the definition: 4 per step.
    if (name == "rk4") {
      EXPECT_EQ(evaluations, 4 * steps);
    }
    const double low = std::stod(row.at("seconds_min")),
                 median = std::stod(row.at("seconds_median")),
                 high = std::stod(row.at("seconds_max"));
    EXPECT_LE(low, median);
    EXPECT_LE(median, high);
  }
  // Its own steps: more as the tolerance falls (about 10^(2/5) per two decades), whatever the
  // output step (the 100 samples).
  ASSERT_EQ(dopri_accepted.size(), 3u);
  EXPECT_GE(dopri_accepted[0], 5u);
  EXPECT_GT(dopri_accepted[1], dopri_accepted[0]);
  EXPECT_GT(dopri_accepted[2], dopri_accepted[1]);
}

TEST_F(BenchCommand, ErrorsFallAsTheStepFalls) {
  ASSERT_EQ(result_.status, 0) << result_.err;
  const Csv csv = read_csv(out() / "results.csv");
  // Rows of one integrator come from the largest step to the smallest.
  std::map<std::string, std::vector<double>> errors;
  for (const auto& row : csv.rows) {
    errors[row.at("integrator")].push_back(std::stod(row.at("orientation_error_final")));
  }
  for (const char* name :
       {"explicit-euler", "semi-implicit-euler", "lie-euler", "implicit-euler", "midpoint",
        "splitting", "splitting4", "moser-veselov", "free-rotor", "rk4", "dopri"}) {
    const auto& e = errors[name];
    for (std::size_t i = 1; i < e.size(); ++i) {
      if (e[i - 1] <= 1e-11) continue;  // at the rounding floor
      EXPECT_LT(e[i], e[i - 1]) << name << " run " << i;
    }
  }
  // free-rotor is exact without torques.
  for (double e : errors["free-rotor"]) EXPECT_LT(e, 1e-12);
  // Splittings keep world L to rounding; the first-order error is far above it.
  for (const auto& row : csv.rows) {
    if (row.at("integrator") != "splitting") continue;
    EXPECT_LT(std::stod(row.at("momentum_error_max")), 1e-12);
  }
}

TEST_F(BenchCommand, PlotsAreValidPngAndSvg) {
  ASSERT_EQ(result_.status, 0) << result_.err;
  for (const char* measure : {"orientation_final", "orientation_max", "omega_max", "momentum_max",
                              "energy_drift", "momentum_norm_drift"}) {
    const std::string stem = std::string("brick_") + measure;
    const std::string png = read_text(out() / (stem + ".png"));
    ASSERT_GT(png.size(), 1000u) << stem;
    EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8)) << stem;
    const std::string svg = read_text(out() / (stem + ".svg"));
    EXPECT_TRUE(svg.rfind("<?xml", 0) == 0 || svg.rfind("<svg", 0) == 0) << stem;
    EXPECT_NE(svg.find("<svg"), std::string::npos) << stem;
    EXPECT_NE(svg.find("</svg>"), std::string::npos) << stem;
    EXPECT_NE(svg.find("<text>explicit-euler</text>"), std::string::npos) << stem;  // legend
    const std::string evaluations = read_text(out() / (stem + "_evaluations.png"));
    EXPECT_EQ(evaluations.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8)) << stem;
    EXPECT_NE(read_text(out() / (stem + "_evaluations.svg")).find("</svg>"), std::string::npos);
  }
  EXPECT_FALSE(std::filesystem::exists(out() / "plots.gnuplot"));
}

TEST_F(BenchCommand, ReportNamesEveryIntegratorTheCoresAndTheFastest) {
  ASSERT_EQ(result_.status, 0) << result_.err;
  const std::string report = read_text(out() / "report.md");
  EXPECT_EQ(report.rfind("# tumble bench\n", 0), 0u);
  for (const auto& info : engine::integrator_catalog()) {
    if (info.name == "exact") continue;
    EXPECT_THAT(report, HasSubstr("| " + info.name + " |")) << info.name;
  }
  EXPECT_THAT(report, HasSubstr("Ran on 1 worker"));
  EXPECT_THAT(report, HasSubstr("exact torque-free solution"));
  EXPECT_THAT(report, HasSubstr("### Fastest to each accuracy"));
  EXPECT_THAT(report, HasSubstr("| 1e-10 |"));
}

TEST_F(BenchCommand, TwoJobsGiveTheSameErrorsAsOne) {
  const auto dir = fresh_directory("bench_jobs");
  const std::string common =
      " --integrators rk4,splitting,dopri --dts 0.04,0.02 "
      "--tolerances 1e-6 --repeat 1 --duration 2 -o ";
  const auto one = bench(scene() + common + "'" + (dir / "one").string() + "' --jobs 1");
  const auto two = bench(scene() + common + "'" + (dir / "two").string() + "' --jobs 2");
  ASSERT_EQ(one.status, 0) << one.err;
  ASSERT_EQ(two.status, 0) << two.err;
  const Csv a = read_csv(dir / "one" / "results.csv");
  const Csv b = read_csv(dir / "two" / "results.csv");
  ASSERT_EQ(a.rows.size(), 5u);
  ASSERT_EQ(b.rows.size(), a.rows.size());
  for (std::size_t i = 0; i < a.rows.size(); ++i) {
    for (const char* column : {"integrator", "dt", "tolerance", "steps", "orientation_error_final",
                               "orientation_error_max", "omega_error_max", "momentum_error_max",
                               "energy_drift_max", "momentum_norm_drift_max"}) {
      EXPECT_EQ(a.rows[i].at(column), b.rows[i].at(column)) << column << " row " << i;
    }
  }
  std::filesystem::remove_all(dir);
}

TEST_F(BenchCommand, ForcedSceneUsesTheCheckedDopriReference) {
  const auto dir = fresh_directory("bench_forced");
  nlohmann::json top = torque_free_scene();
  top["gravity"] = {0, 0, -9.81};
  top["bodies"][0]["pivot"] = {0, 0, -0.1};
  top["duration"] = 1.0;
  std::ofstream(dir / "top.json") << top.dump(2);
  const auto run = bench("'" + (dir / "top.json").string() +
                         "' --integrators rk4 --dts 0.02,0.01,0.005 --repeat 1 -o '" +
                         (dir / "out").string() + "'");
  ASSERT_EQ(run.status, 0) << run.err;
  const std::string report = read_text(dir / "out" / "report.md");
  EXPECT_THAT(report, HasSubstr("dopri at tolerance 1e-13"));
  EXPECT_THAT(report, HasSubstr("reference check (dopri 1e-13 against 1e-12)"));
  const auto observed = std::stod(report.substr(report.find("\n| rk4 | 4 | ") + 12, 5));
  EXPECT_NEAR(observed, 4.0, 0.3);
  std::filesystem::remove_all(dir);
}

// Adaptive integrators only: no fixed steps are planned, so none has to divide the sampling
// interval (the scene's dt); the issue's command on the T-handle failed with "--dts: 0.004
// does not divide the largest step 0.001".
TEST_F(BenchCommand, AdaptiveIntegratorsAloneNeedNoSteps) {
  const auto dir = fresh_directory("bench_adaptive");
  nlohmann::json scene = torque_free_scene();
  scene["absolute_tolerance"] = 0.0;
  std::ofstream(dir / "brick.json") << scene.dump(2);
  const auto run = bench("'" + (dir / "brick.json").string() +
                         "' --integrators dopri --tolerances 1e-6,1e-9 --repeat 1 -o '" +
                         (dir / "out").string() + "'");
  ASSERT_EQ(run.status, 0) << run.err;
  const Csv csv = read_csv(dir / "out" / "results.csv");
  ASSERT_EQ(csv.rows.size(), 2u);
  std::vector<double> errors;
  for (const auto& row : csv.rows) {
    EXPECT_EQ(row.at("integrator"), "dopri");
    EXPECT_EQ(std::stod(row.at("dt")), 0.01);  // sampled on the scene's dt
    EXPECT_EQ(std::stoul(row.at("steps")), 400u);
    errors.push_back(std::stod(row.at("orientation_error_max")));
    EXPECT_LE(errors.back(), 100.0 * std::stod(row.at("tolerance")));
  }
  EXPECT_LT(errors[1], 0.01 * errors[0]);
  // The real scene of the issue, shortened.
  const auto t_handle = bench(std::string("'") + TUMBLE_SOURCE_DIR +
                              "/assets/scenes/t_handle_flip.json' --integrators dopri --duration "
                              "1 --tolerances 1e-6 --repeat 1 -o '" +
                              (dir / "t_handle").string() + "'");
  EXPECT_EQ(t_handle.status, 0) << t_handle.err;
  EXPECT_EQ(read_csv(dir / "t_handle" / "results.csv").rows.size(), 1u);
  std::filesystem::remove_all(dir);
}

TEST_F(BenchCommand, RerunReplacesAPreviousOutputButNotOtherDirectories) {
  const auto dir = fresh_directory("bench_rerun");
  const std::string quick = " --integrators rk4 --dts 0.04 --repeat 1 --duration 0.4 -o ";
  const auto target = "'" + (dir / "out").string() + "'";
  ASSERT_EQ(bench(scene() + quick + target).status, 0);
  const auto again = bench(scene() + quick + target);
  EXPECT_EQ(again.status, 0) << again.err;
  std::filesystem::create_directories(dir / "mine");
  std::ofstream(dir / "mine" / "notes.txt") << "keep";
  const auto refused = bench(scene() + quick + "'" + (dir / "mine").string() + "'");
  EXPECT_EQ(refused.status, 1);
  EXPECT_THAT(refused.err, HasSubstr("neither empty nor a previous bench output"));
  EXPECT_EQ(read_text(dir / "mine" / "notes.txt"), "keep");
  // No temporaries left behind.
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos);
  }
  std::filesystem::remove_all(dir);
}

TEST_F(BenchCommand, InputErrorsExitWithOneAndOneLine) {
  const auto dir = fresh_directory("bench_errors");
  std::ofstream(dir / "file.txt") << "x";
  const std::string o = " -o '" + (dir / "out").string() + "'";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {scene() + " --integrators rk4,warp" + o, "--integrators: unknown integrator 'warp'"},
      {scene() + " --integrators exact" + o, "'exact' is the reference"},
      {scene() + " --dts 0.01,-0.02" + o, "--dts"},
      {scene() + " --dts 0.01,abc" + o, "--dts: expected a positive number, got 'abc'"},
      {scene() + " --dts 0.04,0.03" + o, "does not divide the largest step"},
      {scene() + " --integrators dopri --dts 0.01" + o, "--dts: no fixed-step integrator"},
      {scene() + " --integrators rk4 --tolerances 1e-6" + o, "--tolerances: no adaptive"},
      {scene() + " --tolerances 0" + o, "--tolerances"},
      {scene() + " --repeat 0" + o, "--repeat: expected a whole number >= 1"},
      {scene() + " --jobs x" + o, "--jobs"},
      {scene() + " -o '" + (dir / "file.txt" / "out").string() + "'", "-o: cannot create"},
      {scene() + " -o '" + (dir / "file.txt").string() + "'", "is not a directory"},
      {"'" + (dir / "missing.json").string() + "'" + o, "missing.json"},
  };
  for (const auto& [arguments, message] : cases) {
    const auto run = bench(arguments);
    EXPECT_EQ(run.status, 1) << arguments;
    EXPECT_THAT(run.err, HasSubstr(message)) << arguments;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "out")) << arguments;
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace tumble::app
