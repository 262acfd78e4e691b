// End-to-end tests of `tumble simulate`: the executable, its CSV, its summary and its errors.
#include "app/commands/simulate_command.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "app/support/csv_writer.hpp"
#include "engine/dynamics/integrators.hpp"
#include "support/command_test.hpp"
#include "support/csv_reader.hpp"
#include "support/run_command.hpp"
#include "support/scene_builder.hpp"

namespace tumble::app {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;
using tumble::testing::fresh_directory;
using tumble::testing::read_text;
using tumble::testing::run_command;
using tumble::testing::tumble_executable;

/// One parsed CSV row: the time, the body and the 17 numbers after it.
struct Row {
  double t = 0.0;
  std::string body;
  std::vector<double> values;
};

/// Parses a trajectory CSV; checks every row has 19 fields.
std::vector<Row> read_rows(const std::filesystem::path& file) {
  std::vector<Row> rows;
  for (const std::vector<std::string>& fields : testing::read_csv(file).records) {
    EXPECT_EQ(fields.size(), 19u);
    if (fields.size() != 19u) continue;
    Row row;
    row.t = std::strtod(fields[0].c_str(), nullptr);
    row.body = fields[1];
    for (std::size_t i = 2; i < fields.size(); ++i) {
      row.values.push_back(std::strtod(fields[i].c_str(), nullptr));
    }
    rows.push_back(row);
  }
  return rows;
}

/// A free asymmetric body spinning near its intermediate axis, torque-free.
json free_body_scene(double duration = 0.5, double dt = 0.01) {
  return testing::SceneBuilder()
      .duration(duration)
      .dt(dt)
      .integrator("rk4")
      .body(testing::BodyBuilder("brick")
                .position({1, 2, 3})
                .velocity({0.5, 0, 0})
                .angular_velocity({0.01, 3.0, 0.01}, "body"))
      .json();
}

class SimulateCommand : public testing::CommandTest {
 protected:
  testing::CommandResult simulate(const std::string& arguments) const {
    return run_command(tumble_executable() + " simulate " + arguments);
  }

  /// Names in the test folder that look like temporaries.
  std::vector<std::string> leftovers() const {
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(dir_)) {
      const std::string name = entry.path().filename().string();
      if (name.find(".tmp") != std::string::npos) names.push_back(name);
    }
    return names;
  }
};

TEST_F(SimulateCommand, HelpListsEveryOption) {
  const auto help = run_command(tumble_executable() + " simulate --help");
  EXPECT_EQ(help.status, 0);
  for (const char* option :
       {"SCENE", "--integrator", "--dt", "--duration", "--tolerance", "--absolute-tolerance",
        "--csv", "--every", "--json", "--blowup-factor", "--list-integrators"}) {
    EXPECT_THAT(help.out, HasSubstr(option));
  }
}

TEST_F(SimulateCommand, ListIntegratorsShowsNameOrderAndProperties) {
  const auto list = simulate("--list-integrators");
  ASSERT_EQ(list.status, 0) << list.err;
  for (const auto& info : engine::integrator_catalog()) {
    // One line per integrator: name, order, properties.
    const std::size_t start = list.out.find("\n" + info.name + " ");
    ASSERT_NE(start, std::string::npos) << info.name;
    const std::string line = list.out.substr(start + 1, list.out.find('\n', start + 1) - start - 1);
    const std::string order = info.order < 0 ? "exact" : std::to_string(info.order);
    EXPECT_THAT(line, HasSubstr(" " + order + " ")) << line;
    EXPECT_THAT(line, HasSubstr(info.properties)) << line;
  }
  const auto as_json = simulate("--list-integrators --json");
  ASSERT_EQ(as_json.status, 0) << as_json.err;
  const json parsed = json::parse(as_json.out);
  ASSERT_EQ(parsed.size(), engine::integrator_catalog().size());
  EXPECT_EQ(parsed[0]["name"], engine::integrator_catalog()[0].name);
  EXPECT_EQ(parsed[0]["order"], engine::integrator_catalog()[0].order);
}

TEST_F(SimulateCommand, CsvHasTheExactHeaderAndOneRowPerBodyPerStep) {
  json scene = free_body_scene(0.1, 0.01);
  scene["bodies"].push_back(
      {{"name", "ball"}, {"inertia", {{"principal", {1, 1, 1}}}}, {"mass", 1.0}});
  const auto result = simulate(write_scene(scene) + " --csv " + path("out.csv"));
  ASSERT_EQ(result.status, 0) << result.err;
  const std::string text = read_text(path("out.csv"));
  EXPECT_EQ(text.substr(0, text.find('\n')),
            "t,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,Lx,Ly,Lz,energy");
  const auto rows = read_rows(path("out.csv"));
  ASSERT_EQ(rows.size(), 2u * 11u);  // steps 0..10, two bodies
  EXPECT_EQ(rows.front().t, 0.0);
  EXPECT_EQ(rows.front().body, "brick");
  EXPECT_EQ(rows[1].body, "ball");
  EXPECT_EQ(rows.back().t, 0.1);  // the last step ends exactly at the duration
  EXPECT_TRUE(leftovers().empty());
}

TEST_F(SimulateCommand, FirstRowIsTheSceneState) {
  // Unsorted moments, so the principal frame differs from the body frame: q in the CSV is the
  // user's body orientation, w the world angular velocity, L = R I R^T w, E = w.L/2 + m v^2/2.
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.8, Eigen::Vector3d(1, -2, 0.5).normalized()));
  json scene = free_body_scene();
  scene["bodies"][0]["inertia"] = {{"principal", {3, 1, 2}}};
  scene["bodies"][0]["orientation"] = {q.w(), q.x(), q.y(), q.z()};
  scene["bodies"][0]["angular_velocity_frame"] = "world";
  const auto result = simulate(write_scene(scene) + " --csv " + path("out.csv"));
  ASSERT_EQ(result.status, 0) << result.err;
  const Row row = read_rows(path("out.csv")).at(0);
  const auto& v = row.values;
  EXPECT_EQ(Eigen::Vector3d(v[0], v[1], v[2]), Eigen::Vector3d(1, 2, 3));
  const Eigen::Quaterniond written(v[3], v[4], v[5], v[6]);
  EXPECT_NEAR(std::abs(written.dot(q)), 1.0, 1e-15);
  EXPECT_EQ(Eigen::Vector3d(v[7], v[8], v[9]), Eigen::Vector3d(0.5, 0, 0));
  const Eigen::Vector3d w(0.01, 3.0, 0.01);
  EXPECT_TRUE(Eigen::Vector3d(v[10], v[11], v[12]).isApprox(w, 1e-14));
  const Eigen::Matrix3d r = q.toRotationMatrix();
  const Eigen::Vector3d l = r * Eigen::Vector3d(3, 1, 2).asDiagonal() * r.transpose() * w;
  EXPECT_TRUE(Eigen::Vector3d(v[13], v[14], v[15]).isApprox(l, 1e-14));
  EXPECT_NEAR(v[16], 0.5 * w.dot(l) + 0.5 * 2.0 * 0.25, 1e-14);
}

TEST_F(SimulateCommand, EveryNthStepKeepsTheFirstAndTheLast) {
  const auto result =
      simulate(write_scene(free_body_scene(1.0, 0.01)) + " --every 30 --csv " + path("out.csv"));
  ASSERT_EQ(result.status, 0) << result.err;
  const auto rows = read_rows(path("out.csv"));
  ASSERT_EQ(rows.size(), 5u);  // steps 0, 30, 60, 90 and 100
  const double expected[] = {0.0, 0.3, 0.6, 0.9, 1.0};
  for (std::size_t i = 0; i < rows.size(); ++i) EXPECT_NEAR(rows[i].t, expected[i], 1e-12);
  EXPECT_EQ(rows.back().t, 1.0);

  const auto zero = simulate(write_scene(free_body_scene()) + " --every 0");
  EXPECT_EQ(zero.status, 1);
  EXPECT_THAT(zero.err, HasSubstr("--every: expected a whole number >= 1, got 0"));
}

TEST_F(SimulateCommand, SameSceneGivesABitIdenticalCsv) {
  json scene = free_body_scene(2.0, 0.001);
  scene["gravity"] = {0, 0, -9.81};
  scene["bodies"].push_back({{"name", "top"},
                             {"inertia", {{"principal", {1, 1, 0.5}}}},
                             {"mass", 1.0},
                             {"pivot", {0, 0, -0.3}},
                             {"orientation", {0.99, 0.1, 0, 0}},
                             {"angular_velocity", {0, 0, 20}},
                             {"angular_velocity_frame", "body"}});
  const std::string file = write_scene(scene);
  for (const char* integrator : {"rk4", "dopri", "splitting"}) {
    const auto first = simulate(file + " --integrator " + integrator + " --csv " + path("a.csv"));
    const auto second = simulate(file + " --integrator " + integrator + " --csv " + path("b.csv"));
    ASSERT_EQ(first.status, 0) << first.err;
    ASSERT_EQ(second.status, 0) << second.err;
    const std::string a = read_text(path("a.csv"));
    EXPECT_GT(a.size(), 100000u);
    EXPECT_TRUE(a == read_text(path("b.csv"))) << integrator;
  }
}

TEST_F(SimulateCommand, PivotedBodyKeepsItsCentreOfMassAtAFixedDistance) {
  // A heavy symmetric top: I = (1, 1, 0.5) about the centre of mass, pivot 0.3 below it.
  const json scene = testing::SceneBuilder()
                         .duration(1.0)
                         .dt(0.001)
                         .integrator("rk4")
                         .set("gravity", {0, 0, -9.81})
                         .body(testing::BodyBuilder("top")
                                   .principal({1, 1, 0.5})
                                   .mass(1.0)
                                   .position({0, 0, 0.3})
                                   .set("pivot", {0, 0, -0.3})
                                   .orientation(0.99, 0.1, 0, 0)
                                   .angular_velocity({0, 0, 20}, "body"))
                         .json();
  const auto result = simulate(write_scene(scene) + " --json --csv " + path("top.csv"));
  ASSERT_EQ(result.status, 0) << result.err;
  const auto rows = read_rows(path("top.csv"));
  ASSERT_EQ(rows.size(), 1001u);
  // The pivot sits 0.3 below the initial centre of mass along the tilted body z axis.
  const Eigen::Quaterniond q0 = Eigen::Quaterniond(0.99, 0.1, 0, 0).normalized();
  const Eigen::Vector3d pivot = Eigen::Vector3d(0, 0, 0.3) + q0 * Eigen::Vector3d(0, 0, -0.3);
  double energy_min = rows[0].values[16], energy_max = energy_min;
  for (const Row& row : rows) {
    const Eigen::Vector3d x(row.values[0], row.values[1], row.values[2]);
    const Eigen::Quaterniond q(row.values[3], row.values[4], row.values[5], row.values[6]);
    EXPECT_NEAR((x - pivot).norm(), 0.3, 1e-12);
    EXPECT_TRUE((x - pivot).isApprox(q * Eigen::Vector3d(0, 0, 0.3), 1e-9));
    energy_min = std::min(energy_min, row.values[16]);
    energy_max = std::max(energy_max, row.values[16]);
  }
  EXPECT_LT((energy_max - energy_min) / std::abs(rows[0].values[16]), 1e-8);
  // Gravity torques the top about its pivot, so |L| is no invariant; but it is a Lagrange top
  // (engine/PHYSICS.md §4b): rk4's orientation is measured against the exact heavy top.
  const json summary = json::parse(result.out);
  ASSERT_TRUE(summary["bodies"][0]["orientation_error"].is_number());
  EXPECT_GT(summary["bodies"][0]["orientation_error"].get<double>(), 0.0);
  EXPECT_LT(summary["bodies"][0]["orientation_error"].get<double>(), 1e-6);
  EXPECT_FALSE(summary["bodies"][0]["momentum_conserved"].get<bool>());
  EXPECT_TRUE(summary["bodies"][0]["energy_conserved"].get<bool>());
}

TEST_F(SimulateCommand, JsonSummaryReportsDriftsAndTheExactOrientationError) {
  json scene = free_body_scene(2.0, 0.001);
  scene["bodies"].push_back({{"name", "pushed"},
                             {"inertia", {{"principal", {1, 2, 3}}}},
                             {"mass", 1.0},
                             {"angular_velocity", {0, 1, 0}},
                             {"torque", {0, 0, 0.1}}});
  const auto result = simulate(write_scene(scene) + " --json");
  ASSERT_EQ(result.status, 0) << result.err;
  const json summary = json::parse(result.out);
  EXPECT_EQ(summary["steps"], 2000);
  EXPECT_EQ(summary["total_steps"], 2000);
  EXPECT_EQ(summary["integrator"], "rk4");
  EXPECT_EQ(summary["file"], path("scene.json"));
  EXPECT_EQ(summary["completed"], true);
  EXPECT_TRUE(summary["blow_up"].is_null());
  EXPECT_GT(summary["wall_seconds"].get<double>(), 0.0);
  EXPECT_NEAR(summary["steps_per_second"].get<double>(),
              2000.0 / summary["wall_seconds"].get<double>(),
              1e-6 * summary["steps_per_second"].get<double>());
  ASSERT_EQ(summary["bodies"].size(), 2u);
  const json& free = summary["bodies"][0];
  EXPECT_EQ(free["name"], "brick");
  for (const char* key : {"energy_drift", "momentum_drift"}) {
    EXPECT_GE(free[key]["max"].get<double>(), free[key]["final"].get<double>());
    EXPECT_LT(free[key]["max"].get<double>(), 1e-9) << key;  // RK4 at |w| dt = 0.003
  }
  // RK4 is 4th order: against the exact solution the orientation is good to far below 1e-6.
  ASSERT_TRUE(free["orientation_error"].is_number());
  EXPECT_LT(free["orientation_error"].get<double>(), 1e-8);
  // The torqued body has no exact solution, and its energy changes by the work done.
  const json& pushed = summary["bodies"][1];
  EXPECT_TRUE(pushed["orientation_error"].is_null());
  EXPECT_FALSE(pushed["energy_conserved"].get<bool>());
  // A constant world torque adds to L linearly: L(2) = (0, 2, 0) + 2 (0, 0, 0.1).
  EXPECT_NEAR(pushed["momentum_drift"]["final"].get<double>(), std::sqrt(4.04) / 2.0 - 1.0, 1e-12);

  // A low-order integrator shows a larger error than RK4 on the same run.
  const auto euler = simulate(write_scene(scene) + " --json --integrator explicit-euler");
  ASSERT_EQ(euler.status, 0) << euler.err;
  EXPECT_GT(json::parse(euler.out)["bodies"][0]["orientation_error"].get<double>(), 1e-4);
}

TEST_F(SimulateCommand, TextSummary) {
  const auto result = simulate(write_scene(free_body_scene()) + " --csv " + path("out.csv"));
  ASSERT_EQ(result.status, 0) << result.err;
  for (const char* text : {"rk4, dt 0.01 s, 50 of 50 steps to t = 0.5 s", "steps/s", "body 'brick'",
                           "energy drift", "|L| drift", "orientation error",
                           "rad against the exact torque-free solution", "(51 rows)"}) {
    EXPECT_THAT(result.out, HasSubstr(text));
  }
}

TEST_F(SimulateCommand, CommandLineOverridesTheScene) {
  const auto result =
      simulate(write_scene(free_body_scene()) +
               " --dt 0.02 --duration 0.2 --integrator splitting --json --csv " + path("out.csv"));
  ASSERT_EQ(result.status, 0) << result.err;
  const json summary = json::parse(result.out);
  EXPECT_EQ(summary["integrator"], "splitting");
  EXPECT_EQ(summary["steps"], 10);
  EXPECT_EQ(summary["dt"], 0.02);
  EXPECT_EQ(read_rows(path("out.csv")).size(), 11u);

  // --tolerance reaches the adaptive integrator: a tighter one is closer to the exact solution.
  const std::string file = write_scene(free_body_scene(5.0, 0.1));
  const auto loose = simulate(file + " --integrator dopri --tolerance 1e-5 --json");
  const auto tight = simulate(file + " --integrator dopri --tolerance 1e-11 --json");
  ASSERT_EQ(loose.status, 0) << loose.err;
  ASSERT_EQ(tight.status, 0) << tight.err;
  EXPECT_GT(json::parse(loose.out)["bodies"][0]["orientation_error"].get<double>(),
            100 * json::parse(tight.out)["bodies"][0]["orientation_error"].get<double>());
  // So does --absolute-tolerance: 1 rad of orientation a step lets the error grow.
  const auto absolute =
      simulate(file + " --integrator dopri --tolerance 1e-11 --absolute-tolerance 1 --json");
  ASSERT_EQ(absolute.status, 0) << absolute.err;
  EXPECT_GT(json::parse(absolute.out)["bodies"][0]["orientation_error"].get<double>(),
            100 * json::parse(tight.out)["bodies"][0]["orientation_error"].get<double>());
  for (const char* value : {"-1e-9", "inf", "nan"}) {
    const auto refused =
        simulate(file + " --integrator dopri --absolute-tolerance " + std::string(value));
    EXPECT_EQ(refused.status, 1) << value;
    EXPECT_THAT(refused.err, HasSubstr("--absolute-tolerance: expected a finite number >= 0"))
        << value;
  }
  const auto zero_tolerance = simulate(file + " --integrator dopri --tolerance 0");
  EXPECT_EQ(zero_tolerance.status, 1);
  EXPECT_THAT(zero_tolerance.err, HasSubstr("--tolerance: expected a positive finite number"));

  const auto bad = simulate(write_scene(free_body_scene()) + " --integrator leapfrog");
  EXPECT_EQ(bad.status, 1);
  EXPECT_THAT(bad.err,
              HasSubstr("--integrator: unknown integrator \"leapfrog\"; expected one of:"));
  EXPECT_THAT(bad.err, HasSubstr("rk4"));
  const auto negative = simulate(write_scene(free_body_scene()) + " --dt=-1");
  EXPECT_EQ(negative.status, 1);
  EXPECT_THAT(negative.err, HasSubstr("--dt: expected a positive finite number, got -1"));
  const auto longer = simulate(write_scene(free_body_scene()) + " --dt 1");
  EXPECT_EQ(longer.status, 1);
  EXPECT_THAT(longer.err, HasSubstr("--dt: expected a step no longer than the duration (0.5 s)"));
  const auto factor = simulate(write_scene(free_body_scene()) + " --blowup-factor 0.5");
  EXPECT_EQ(factor.status, 1);
  EXPECT_THAT(factor.err, HasSubstr("--blowup-factor: expected a growth factor > 1"));
}

TEST_F(SimulateCommand, BlowUpExitsWithThreeAndKeepsAValidCsv) {
  // Explicit Euler on a needle (1 : 1000 : 1000) spinning fast about its axis, large dt.
  const json scene = testing::SceneBuilder()
                         .duration(10.0)
                         .dt(0.01)
                         .integrator("explicit-euler")
                         .body(testing::BodyBuilder("needle")
                                   .principal({0.001, 1, 1})
                                   .mass(1.0)
                                   .angular_velocity({10, 1, 0}))
                         .json();
  std::ofstream(path("out.csv")) << "an older file\n";
  const auto result = simulate(write_scene(scene) + " --every 7 --json --csv " + path("out.csv"));
  EXPECT_EQ(result.status, 3);
  // One line on stderr naming the body, the step and the time.
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  EXPECT_THAT(result.err, HasSubstr("tumble simulate: blow-up: body 'needle' at step "));
  EXPECT_THAT(result.err, HasSubstr(" (t = "));
  const json summary = json::parse(result.out);
  EXPECT_EQ(summary["completed"], false);
  const std::size_t good_steps = summary["steps"];
  ASSERT_GT(good_steps, 0u);
  EXPECT_LT(good_steps, 1000u);
  EXPECT_THAT(result.err, HasSubstr("at step " + std::to_string(good_steps + 1) + " "));

  // The CSV replaced the old file, holds every 7th step and the last good one, all finite.
  const std::string text = read_text(path("out.csv"));
  EXPECT_EQ(text.substr(0, text.find('\n')), std::string(kTrajectoryHeader));
  EXPECT_EQ(text.back(), '\n');
  const auto rows = read_rows(path("out.csv"));
  ASSERT_EQ(rows.size(), good_steps / 7 + 1 + (good_steps % 7 != 0 ? 1 : 0));
  EXPECT_NEAR(rows.back().t, 0.01 * static_cast<double>(good_steps), 1e-9);
  for (const Row& row : rows) {
    for (double value : row.values) EXPECT_TRUE(std::isfinite(value));
  }
  EXPECT_EQ(summary["csv_rows"].get<std::size_t>(), rows.size());
  EXPECT_TRUE(leftovers().empty());

  // A larger --blowup-factor lets the same run go on for longer before it is stopped.
  const auto tolerant = simulate(write_scene(scene) + " --json --blowup-factor 1000");
  EXPECT_EQ(tolerant.status, 3);
  EXPECT_GT(json::parse(tolerant.out)["steps"].get<std::size_t>(), good_steps);
}

TEST_F(SimulateCommand, StiffSpringBlowsUpUnderSymplecticEuler) {
  // wn = 100 rad/s: symplectic Euler is stable for wn dt < 2; here wn dt = 2.5.
  const json scene =
      testing::SceneBuilder()
          .duration(1.0)
          .dt(0.025)
          .integrator("semi-implicit-euler")
          .body(testing::BodyBuilder("bob")
                    .principal({1, 1, 1})
                    .mass(1.0)
                    .position({0.1, 0, 0})
                    .set("spring",
                         {{"anchor", {0, 0, 0}}, {"attach", {0, 0, 0}}, {"stiffness", 1e4}}))
          .json();
  const auto result = simulate(write_scene(scene) + " --csv " + path("out.csv"));
  EXPECT_EQ(result.status, 3);
  EXPECT_THAT(result.err, HasSubstr("body 'bob' at step 1 (t = 0.025 s)"));
  EXPECT_EQ(read_rows(path("out.csv")).size(), 1u);  // the initial state
  // Below the limit (wn dt = 1.5) the same spring runs to the end.
  const auto stable = simulate(write_scene(scene) + " --dt 0.015");
  EXPECT_EQ(stable.status, 0) << stable.err;
}

TEST_F(SimulateCommand, UnwritableCsvPathFailsBeforeSimulating) {
  const std::string missing = path("no/such/folder/out.csv");
  // A run of 1e8 steps would take most of a minute: the error must come first.
  const auto result =
      simulate(write_scene(free_body_scene(100.0, 1e-6)) + " --every 100 --csv " + missing);
  EXPECT_EQ(result.status, 1);
  EXPECT_THAT(result.err, HasSubstr("cannot write '" + missing + "'"));
  EXPECT_EQ(result.out, "");
  const auto directory = simulate(write_scene(free_body_scene()) + " --csv " + dir_.string());
  EXPECT_EQ(directory.status, 1);
  EXPECT_THAT(directory.err, HasSubstr("cannot write '" + dir_.string() + "': it is a directory"));
}

TEST_F(SimulateCommand, FailureAfterOpeningTheCsvLeavesNoFile) {
  // The exact integrator refuses torques, after the CSV's temporary exists: it must go, and
  // an existing file under the final name must stay as it was.
  json scene = free_body_scene();
  scene["integrator"] = "exact";
  scene["bodies"][0]["torque"] = {0, 0, 1};
  std::ofstream(path("kept.csv")) << "old\n";
  const auto result = simulate(write_scene(scene) + " --csv " + path("kept.csv"));
  EXPECT_EQ(result.status, 1);
  EXPECT_THAT(result.err, HasSubstr("tumble simulate: error: " + path("scene.json") + ": "));
  EXPECT_THAT(result.err, HasSubstr("brick"));
  EXPECT_EQ(read_text(path("kept.csv")), "old\n");
  const auto fresh = simulate(write_scene(scene) + " --csv " + path("new.csv"));
  EXPECT_EQ(fresh.status, 1);
  EXPECT_FALSE(std::filesystem::exists(path("new.csv")));
  EXPECT_TRUE(leftovers().empty());
}

TEST_F(SimulateCommand, SceneErrorsExitWithOne) {
  json scene = free_body_scene();
  scene["bodies"][0]["angular_velocity"] = {1, "fast", 3};
  const std::string file = write_scene(scene);
  const auto result = simulate(file + " --csv " + path("out.csv"));
  EXPECT_EQ(result.status, 1);
  EXPECT_THAT(result.err, HasSubstr(file + ": bodies[0].angular_velocity[1]: expected a number"));
  EXPECT_FALSE(std::filesystem::exists(path("out.csv")));
  const auto no_scene = simulate("");
  EXPECT_EQ(no_scene.status, 1);
  EXPECT_THAT(no_scene.err, HasSubstr("a SCENE file is required"));
  const auto missing = simulate(path("nowhere.json"));
  EXPECT_EQ(missing.status, 1);
  EXPECT_THAT(missing.err, HasSubstr("nowhere.json: cannot open the scene file"));
}

TEST_F(SimulateCommand, MeshScenesResolvePathsAgainstTheSceneFile) {
  std::filesystem::create_directories(dir_ / "scenes");
  json scene = free_body_scene(0.05, 0.01);
  scene["bodies"][0].erase("inertia");
  scene["bodies"][0]["mesh"] = std::string(TUMBLE_SOURCE_DIR) + "/assets/meshes/t_handle.obj";
  const auto absolute = simulate(write_scene(scene, "scenes/abs.json") + " --json");
  ASSERT_EQ(absolute.status, 0) << absolute.err;
  scene["bodies"][0]["mesh"] = "../meshes/none.obj";
  const auto relative = simulate(write_scene(scene, "scenes/rel.json"));
  EXPECT_EQ(relative.status, 1);
  EXPECT_THAT(relative.err, HasSubstr("scenes/rel.json: bodies[0].mesh: "));
  EXPECT_THAT(relative.err, HasSubstr("scenes/../meshes/none.obj"));
}

TEST(CsvNumbers, SeventeenSignificantDigitsAndQuotedNames) {
  std::string out;
  append_number(out, 0.1);
  EXPECT_EQ(out, "0.10000000000000001");
  out.clear();
  append_number(out, 1.0 / 3.0);
  EXPECT_EQ(std::strtod(out.c_str(), nullptr), 1.0 / 3.0);
  out.clear();
  append_csv_field(out, "plain");
  append_csv_field(out, "a,\"b\"");
  EXPECT_EQ(out, "plain\"a,\"\"b\"\"\"");
  out.clear();
  append_csv_field(out, "two\nlines");
  EXPECT_EQ(out, "\"two\nlines\"");
}

}  // namespace
}  // namespace tumble::app
