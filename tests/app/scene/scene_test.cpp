// Scene files: every validation error names the file and the JSON path; compilation puts the
// right inertia, frames, initial momentum and force terms (only those asked for) on each body.
#include "app/scene/scene.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <variant>

#include <nlohmann/json.hpp>

#include "base/errors.hpp"
#include "support/input_error.hpp"
#include "support/run_command.hpp"
#include "support/scene_builder.hpp"

namespace tumble::app {
namespace {

using nlohmann::json;
using ::testing::AllOf;
using ::testing::HasSubstr;

const std::filesystem::path kSceneFile = "scenes/flip.json";

/// A valid one-body scene to break in one place.
json base_scene() {
  return testing::SceneBuilder().duration(1.0).dt(0.01).body(testing::BodyBuilder("brick")).json();
}

/// The message parse_scene throws for `text` (empty, with a test failure, when it accepts it).
std::string error_of_text(const std::string& text) {
  return testing::input_error_of([&] { parse_scene(text, kSceneFile); }, text);
}
std::string scene_error_of(const json& scene) {
  return error_of_text(scene.dump());
}

/// The base scene with body 0's `key` set to `value`.
json with_body(const std::string& key, const json& value) {
  json scene = base_scene();
  scene["bodies"][0][key] = value;
  return scene;
}

/// Writes a closed, outward-wound OBJ box of size `s`, centred at `c`.
void write_box_obj(const std::filesystem::path& file, const Eigen::Vector3d& s,
                   const Eigen::Vector3d& c) {
  std::filesystem::create_directories(file.parent_path());
  std::ofstream out(file);
  out.precision(17);
  for (int i = 0; i < 8; ++i) {
    out << "v " << c.x() + ((i & 1) ? 0.5 : -0.5) * s.x() << " "
        << c.y() + ((i & 2) ? 0.5 : -0.5) * s.y() << " " << c.z() + ((i & 4) ? 0.5 : -0.5) * s.z()
        << "\n";
  }
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    out << "f " << q[0] + 1 << " " << q[1] + 1 << " " << q[2] + 1 << "\n";
    out << "f " << q[0] + 1 << " " << q[2] + 1 << " " << q[3] + 1 << "\n";
  }
}

template <typename Term>
int count_terms(const engine::BodyModel& body) {
  int count = 0;
  for (const auto& term : body.forces) count += std::holds_alternative<Term>(term) ? 1 : 0;
  return count;
}

// ---------------------------------------------------------------------------------------------
// Parsing: accepted forms and defaults.

TEST(SceneParse, DefaultsOfAMinimalScene) {
  const SceneDescription scene = parse_scene(base_scene().dump(), kSceneFile);
  EXPECT_EQ(scene.name, "flip");  // the file's stem
  EXPECT_EQ(scene.integrator, "rk4");
  EXPECT_EQ(scene.duration, 1.0);
  EXPECT_EQ(scene.dt, 0.01);
  EXPECT_FALSE(scene.gravity.has_value());
  ASSERT_EQ(scene.bodies.size(), 1u);
  const BodyDescription& body = scene.bodies[0];
  EXPECT_EQ(body.name, "brick");
  EXPECT_FALSE(body.mesh.has_value());
  EXPECT_EQ(*body.principal_moments, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(*body.mass, 2.0);
  EXPECT_TRUE(body.orientation.coeffs().isApprox(Eigen::Quaterniond::Identity().coeffs()));
  EXPECT_EQ(body.angular_velocity_frame, VectorFrame::kWorld);
  EXPECT_FALSE(body.pivot || body.torque || body.spring || body.velocity);
}

TEST(SceneParse, TheIssueExampleWithCommentsParses) {
  const std::string text = R"({ "name": "T-handle flip",
    "duration": 20.0, "dt": 0.001, "integrator": "rk4",
    "gravity": [0, 0, -9.81],                 // optional; absent = none
    "bodies": [{
      "name": "handle",
      "mesh": "../meshes/t_handle.obj",
      "mass": 1.0, "scale": 1.0,
      "position": [0, 0, 0],
      "orientation": [1, 0, 0, 0],            /* w, x, y, z */
      "angular_velocity": [0.01, 5.0, 0.01],
      "angular_velocity_frame": "body",
      "pivot": [0, 0, -0.4],
      "torque": [0, 0, 0], "torque_frame": "world",
      "spring": {"anchor": [0,0,1], "attach": [0,0,0.1], "stiffness": 1e4, "damping": 0}
    }] })";
  const SceneDescription scene = parse_scene(text, kSceneFile);
  EXPECT_EQ(scene.name, "T-handle flip");
  EXPECT_EQ(*scene.gravity, Eigen::Vector3d(0, 0, -9.81));
  const BodyDescription& body = scene.bodies.at(0);
  // Mesh paths are relative to the scene file.
  EXPECT_EQ(*body.mesh, std::filesystem::path("scenes/../meshes/t_handle.obj"));
  EXPECT_EQ(body.angular_velocity_frame, VectorFrame::kBody);
  EXPECT_EQ(*body.pivot, Eigen::Vector3d(0, 0, -0.4));
  EXPECT_EQ(body.spring->stiffness, 1e4);
  EXPECT_EQ(body.spring->attach, Eigen::Vector3d(0, 0, 0.1));
}

TEST(SceneParse, AnyNonZeroQuaternionIsNormalised) {
  const auto scene = parse_scene(with_body("orientation", {2, 0, 0, 2}).dump(), kSceneFile);
  const Eigen::Quaterniond& q = scene.bodies[0].orientation;
  EXPECT_NEAR(q.norm(), 1.0, 1e-15);
  EXPECT_NEAR(q.w(), std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(q.z(), std::sqrt(0.5), 1e-15);
}

TEST(SceneParse, UnnamedBodiesGetTheirIndex) {
  json scene = base_scene();
  scene["bodies"][0].erase("name");
  EXPECT_EQ(parse_scene(scene.dump(), kSceneFile).bodies[0].name, "body0");
}

// ---------------------------------------------------------------------------------------------
// Parsing: every error names the file, the JSON path and what was expected.

TEST(SceneErrors, MalformedJsonGivesLineAndColumn) {
  const std::string message = error_of_text("{\n  \"duration\": 1,\n  \"dt\": ,\n}");
  EXPECT_THAT(message, HasSubstr("scenes/flip.json:3:9: malformed JSON"));
  EXPECT_THAT(error_of_text(""), HasSubstr("scenes/flip.json:1:1: malformed JSON"));
}

TEST(SceneErrors, DuplicateKeysAreRefused) {
  // nlohmann would keep the last "dt" silently.
  EXPECT_THAT(error_of_text(R"({"duration": 1, "dt": 0.1, "bodies": [{"mass": 1, "mass": 2}]})"),
              HasSubstr("scenes/flip.json: bodies[0].mass: duplicate key"));
}

TEST(SceneErrors, TopLevelMustBeAnObject) {
  EXPECT_THAT(error_of_text("[1, 2]"),
              HasSubstr("scenes/flip.json: (top level): expected an object"));
}

TEST(SceneErrors, UnknownKeysAreNamed) {
  json scene = base_scene();
  scene["gravitty"] = {0, 0, -9.81};
  EXPECT_THAT(scene_error_of(scene),
              AllOf(HasSubstr("scenes/flip.json: gravitty: unknown key"), HasSubstr("gravity")));
  EXPECT_THAT(scene_error_of(with_body("colour", "red")),
              AllOf(HasSubstr("bodies[0].colour: unknown key; expected one of: name, mesh")));
  json spring = with_body(
      "spring", {{"anchor", {0, 0, 1}}, {"attach", {0, 0, 0}}, {"stiffness", 1}, {"k", 2}});
  EXPECT_THAT(scene_error_of(spring), HasSubstr("bodies[0].spring.k: unknown key"));
  EXPECT_THAT(scene_error_of(with_body("inertia", {{"diagonal", {1, 1, 1}}})),
              HasSubstr("bodies[0].inertia.diagonal: unknown key"));
}

TEST(SceneErrors, WrongTypesSayWhatWasExpected) {
  EXPECT_THAT(scene_error_of(with_body("angular_velocity", "fast")),
              HasSubstr("scenes/flip.json: bodies[0].angular_velocity: expected an array of 3 "
                        "finite numbers [x, y, z], got the string \"fast\""));
  EXPECT_THAT(scene_error_of(with_body("angular_velocity", {1, 2})),
              HasSubstr("bodies[0].angular_velocity: expected an array of 3 finite numbers"));
  EXPECT_THAT(scene_error_of(with_body("angular_velocity", {1, true, 2})),
              HasSubstr("bodies[0].angular_velocity[1]: expected a number, got true"));
  EXPECT_THAT(scene_error_of(with_body("mass", "2 kg")),
              HasSubstr("bodies[0].mass: expected a number, got the string \"2 kg\""));
  EXPECT_THAT(scene_error_of(with_body("name", 7)), HasSubstr("bodies[0].name: expected a string"));
  json mesh = with_body("mesh", json::array());
  mesh["bodies"][0].erase("inertia");
  EXPECT_THAT(scene_error_of(mesh), HasSubstr("bodies[0].mesh: expected a string"));
  json scene = base_scene();
  scene["bodies"][0] = 5;
  EXPECT_THAT(scene_error_of(scene), HasSubstr("bodies[0]: expected an object, got 5"));
}

TEST(SceneErrors, MissingRequiredFields) {
  for (const char* key : {"duration", "dt", "bodies"}) {
    json scene = base_scene();
    scene.erase(key);
    EXPECT_THAT(scene_error_of(scene),
                HasSubstr(std::string("scenes/flip.json: ") + key + ": missing"));
  }
  json no_mass = base_scene();
  no_mass["bodies"][0].erase("mass");
  EXPECT_THAT(scene_error_of(no_mass), HasSubstr("bodies[0]: missing \"mass\" (kg)"));
  EXPECT_THAT(scene_error_of(with_body("spring", {{"attach", {0, 0, 0}}, {"stiffness", 1}})),
              HasSubstr("bodies[0].spring.anchor: missing"));
  EXPECT_THAT(scene_error_of(with_body("spring", {{"anchor", {0, 0, 0}}, {"attach", {0, 0, 0}}})),
              HasSubstr("bodies[0].spring.stiffness: missing"));
}

TEST(SceneErrors, DurationAndStep) {
  json scene = base_scene();
  scene["duration"] = 0;
  EXPECT_THAT(scene_error_of(scene), HasSubstr("duration: expected a positive number, got 0"));
  scene = base_scene();
  scene["dt"] = -0.01;
  EXPECT_THAT(scene_error_of(scene), HasSubstr("dt: expected a positive number, got -0.01"));
  scene = base_scene();
  scene["dt"] = 2.0;
  EXPECT_THAT(scene_error_of(scene),
              HasSubstr("dt: expected a step no longer than the duration (1 s), got 2"));
  scene = base_scene();
  scene["dt"] = 1e-300;
  EXPECT_THAT(scene_error_of(scene),
              HasSubstr("dt: expected at most 1e12 steps, but a duration of 1 s "
                        "takes 1e+300 steps of 1e-300 s"));
  scene = base_scene();
  scene["tolerance"] = 0;
  EXPECT_THAT(scene_error_of(scene), HasSubstr("tolerance: expected a positive number"));
  scene = base_scene();
  scene["absolute_tolerance"] = -1e-9;
  EXPECT_THAT(scene_error_of(scene),
              HasSubstr("absolute_tolerance: expected a number >= 0, got -1e-09"));
  scene = base_scene();
  scene["absolute_tolerance"] = "small";
  EXPECT_THAT(scene_error_of(scene), HasSubstr("absolute_tolerance: expected a number"));
}

TEST(SceneTolerances, ReachTheSimulationSettings) {
  json scene = base_scene();
  EXPECT_FALSE(parse_scene(scene.dump(), kSceneFile).absolute_tolerance.has_value());
  scene["tolerance"] = 1e-7;
  scene["absolute_tolerance"] = 0.0;  // zero is allowed: a purely relative norm
  EXPECT_EQ(parse_scene(scene.dump(), kSceneFile).absolute_tolerance, 0.0);
  scene["absolute_tolerance"] = 1e-9;
  const engine::SimulationSettings settings =
      simulation_settings(parse_scene(scene.dump(), kSceneFile));
  EXPECT_EQ(settings.tolerance, 1e-7);
  EXPECT_EQ(settings.absolute_tolerance, 1e-9);
}

TEST(SceneErrors, UnknownIntegratorListsTheValidNames) {
  json scene = base_scene();
  scene["integrator"] = "leapfrog";
  EXPECT_THAT(scene_error_of(scene), AllOf(HasSubstr("integrator: unknown integrator \"leapfrog\"; "
                                                     "expected one of: "),
                                           HasSubstr("rk4")));
}

TEST(SceneErrors, BodiesMustBeANonEmptyArray) {
  json scene = base_scene();
  scene["bodies"] = json::array();
  EXPECT_THAT(scene_error_of(scene),
              HasSubstr("bodies: expected a non-empty array of bodies, got an array of 0"));
  scene["bodies"] = json::object();
  EXPECT_THAT(scene_error_of(scene),
              HasSubstr("bodies: expected a non-empty array of bodies, got an object"));
}

TEST(SceneErrors, ExactlyOneOfMeshOrInertia) {
  EXPECT_THAT(scene_error_of(with_body("mesh", "box.obj")),
              HasSubstr("bodies[0]: expected exactly one of \"mesh\", \"shape\" or \"inertia\", "
                        "got 2 of them"));
  json scene = base_scene();
  scene["bodies"][0].erase("inertia");
  EXPECT_THAT(scene_error_of(scene),
              AllOf(HasSubstr("bodies[0]: expected exactly one of \"mesh\" (a "
                              "file), \"shape\" ({\"box\": [x, y, z]}"),
                    HasSubstr("got none")));
  EXPECT_THAT(scene_error_of(with_body("inertia", {{"principal", {1, 2, 3}},
                                                   {"tensor", {{1, 0, 0}, {0, 2, 0}, {0, 0, 3}}}})),
              HasSubstr("bodies[0].inertia: expected exactly one of \"principal\""));
}

TEST(SceneErrors, MassDensityAndScale) {
  EXPECT_THAT(scene_error_of(with_body("density", 1000)),
              HasSubstr("bodies[0].density: \"mass\" and \"density\" exclude each other"));
  json scene = base_scene();
  scene["bodies"][0].erase("mass");
  scene["bodies"][0]["density"] = 1000;
  EXPECT_THAT(scene_error_of(scene), HasSubstr("bodies[0].density: \"density\" needs a mesh"));
  EXPECT_THAT(scene_error_of(with_body("mass", 0)),
              HasSubstr("bodies[0].mass: expected a positive number, got 0"));
  EXPECT_THAT(scene_error_of(with_body("scale", 2)),
              HasSubstr("bodies[0].scale: \"scale\" applies to a mesh only"));
  json mesh = base_scene();
  mesh["bodies"][0].erase("inertia");
  mesh["bodies"][0]["mesh"] = "box.obj";
  mesh["bodies"][0]["scale"] = -1;
  EXPECT_THAT(scene_error_of(mesh),
              HasSubstr("bodies[0].scale: expected a positive number, got -1"));
  mesh["bodies"][0].erase("scale");
  mesh["bodies"][0]["allow_overlap"] = 1;
  EXPECT_THAT(scene_error_of(mesh),
              HasSubstr("bodies[0].allow_overlap: expected true or false, got 1"));
  mesh["bodies"][0]["allow_overlap"] = true;
  EXPECT_EQ(parse_scene(mesh.dump(), kSceneFile).bodies[0].overlap, engine::OverlapMode::kSum);
  mesh["bodies"][0]["allow_overlap"] = false;
  EXPECT_EQ(parse_scene(mesh.dump(), kSceneFile).bodies[0].overlap, engine::OverlapMode::kRefuse);
  mesh["bodies"][0]["overlap"] = "sum";
  EXPECT_THAT(
      scene_error_of(mesh),
      HasSubstr("bodies[0].allow_overlap: give \"overlap\" or \"allow_overlap\", not both"));
  mesh["bodies"][0].erase("allow_overlap");
  EXPECT_EQ(parse_scene(mesh.dump(), kSceneFile).bodies[0].overlap, engine::OverlapMode::kSum);
  mesh["bodies"][0]["overlap"] = "refuse";
  EXPECT_EQ(parse_scene(mesh.dump(), kSceneFile).bodies[0].overlap, engine::OverlapMode::kRefuse);
  mesh["bodies"][0]["overlap"] = "merge";
  EXPECT_THAT(scene_error_of(mesh),
              HasSubstr("bodies[0].overlap: expected \"union\", \"sum\" or \"refuse\", got "
                        "\"merge\""));
  mesh["bodies"][0].erase("overlap");
  EXPECT_EQ(parse_scene(mesh.dump(), kSceneFile).bodies[0].overlap, engine::OverlapMode::kUnion);
  mesh["bodies"][0].erase("mass");
  EXPECT_THAT(scene_error_of(mesh), HasSubstr("bodies[0]: missing \"mass\" (kg) or \"density\""));
  EXPECT_THAT(scene_error_of(with_body("allow_overlap", true)),
              HasSubstr("bodies[0].allow_overlap: \"allow_overlap\" applies to a mesh only"));
}

TEST(SceneErrors, HugeNumbersReadAsInfinityAreRefused) {
  // JSON has no NaN or Inf literal, but 1e999 overflows to inf when read.
  std::string text = base_scene().dump();
  text.replace(text.find("\"mass\":2.0"), 10, "\"mass\":1e999");
  EXPECT_THAT(error_of_text(text),
              AllOf(HasSubstr("scenes/flip.json:1:"),
                    HasSubstr(": bodies[0].mass: expected a finite number, got "
                              "1e999 (beyond the range of a double)")));
  const std::string omega = R"({"duration": 1, "dt": 0.1, "bodies": [{"inertia": {"principal":
      [1, 1, 1]}, "mass": 1, "angular_velocity": [0, -1e999, 0]}]})";
  EXPECT_THAT(error_of_text(omega),
              HasSubstr("bodies[0].angular_velocity[1]: expected a finite number, "
                        "got -1e999"));
  const std::string duration = R"({"duration": 1e400, "dt": 0.1, "bodies": []})";
  EXPECT_THAT(error_of_text(duration),
              HasSubstr("scenes/flip.json:1:14: duration: expected a finite number, got 1e400"));
}

TEST(SceneErrors, PrincipalMomentsMustBeARigidBody) {
  EXPECT_THAT(scene_error_of(with_body("inertia", {{"principal", {1, -2, 3}}})),
              AllOf(HasSubstr("bodies[0].inertia.principal: "), HasSubstr("positive")));
  EXPECT_THAT(scene_error_of(with_body("inertia", {{"principal", {1, 1, 3}}})),
              AllOf(HasSubstr("bodies[0].inertia.principal: "), HasSubstr("triangle inequality")));
}

TEST(SceneErrors, TensorMustBeSymmetricPositiveDefinite) {
  EXPECT_THAT(
      scene_error_of(with_body("inertia", {{"tensor", {{2, 0.5, 0}, {0, 2, 0}, {0, 0, 3}}}})),
      HasSubstr("bodies[0].inertia.tensor: expected a symmetric tensor, but [0][1] = 0.5 "
                "differs from [1][0] = 0"));
  EXPECT_THAT(scene_error_of(with_body("inertia", {{"tensor", {{1, 2, 0}, {2, 1, 0}, {0, 0, 1}}}})),
              HasSubstr("bodies[0].inertia.tensor: expected a positive definite tensor; its "
                        "principal moments are [-"));
  EXPECT_THAT(scene_error_of(with_body("inertia", {{"tensor", {{1, 0, 0}, {0, 1, 0}, {0, 0, 5}}}})),
              AllOf(HasSubstr("bodies[0].inertia.tensor: "), HasSubstr("triangle inequality")));
  EXPECT_THAT(scene_error_of(with_body("inertia", {{"tensor", {{1, 0, 0}, {0, 1, 0}}}})),
              HasSubstr("bodies[0].inertia.tensor: expected a 3 x 3 array"));
  EXPECT_THAT(scene_error_of(with_body("inertia", {{"tensor", {{1, 0, 0}, {0, 1}, {0, 0, 1}}}})),
              HasSubstr("bodies[0].inertia.tensor[1]: expected a row of 3 finite numbers"));
}

TEST(SceneErrors, Quaternions) {
  EXPECT_THAT(scene_error_of(with_body("orientation", {0, 0, 0, 0})),
              HasSubstr("bodies[0].orientation: expected a non-zero quaternion [w, x, y, z]"));
  EXPECT_THAT(scene_error_of(with_body("orientation", {1, 0, 0})),
              HasSubstr("bodies[0].orientation: expected a quaternion [w, x, y, z] of 4"));
}

TEST(SceneErrors, Frames) {
  EXPECT_THAT(scene_error_of(with_body("angular_velocity_frame", "sideways")),
              HasSubstr("bodies[0].angular_velocity_frame: given without \"angular_velocity\""));
  json scene = with_body("angular_velocity", {0, 0, 1});
  scene["bodies"][0]["angular_velocity_frame"] = "sideways";
  EXPECT_THAT(scene_error_of(scene),
              HasSubstr("bodies[0].angular_velocity_frame: expected \"world\" or "
                        "\"body\", got \"sideways\""));
  scene = with_body("torque", {0, 0, 1});
  scene["bodies"][0]["torque_frame"] = "Body";
  EXPECT_THAT(scene_error_of(scene),
              HasSubstr("bodies[0].torque_frame: expected \"world\" or \"body\""));
  EXPECT_THAT(scene_error_of(with_body("torque_frame", "body")),
              HasSubstr("bodies[0].torque_frame: given without \"torque\""));
}

TEST(SceneErrors, SpringConstants) {
  EXPECT_THAT(scene_error_of(with_body(
                  "spring", {{"anchor", {0, 0, 1}}, {"attach", {0, 0, 0}}, {"stiffness", -1}})),
              HasSubstr("bodies[0].spring.stiffness: expected a number >= 0, got -1"));
  EXPECT_THAT(
      scene_error_of(with_body(
          "spring",
          {{"anchor", {0, 0, 1}}, {"attach", {0, 0, 0}}, {"stiffness", 1}, {"damping", -0.5}})),
      HasSubstr("bodies[0].spring.damping: expected a number >= 0, got -0.5"));
}

TEST(SceneErrors, PivotedBodiesTakeNoVelocity) {
  json scene = with_body("pivot", {0, 0, -0.4});
  scene["bodies"][0]["velocity"] = {1, 0, 0};
  EXPECT_THAT(scene_error_of(scene),
              HasSubstr("bodies[0].velocity: a pivoted body takes no \"velocity\""));
}

TEST(SceneErrors, BodyNamesAreUniqueAndPrintable) {
  json scene = base_scene();
  scene["bodies"].push_back(scene["bodies"][0]);
  EXPECT_THAT(scene_error_of(scene),
              HasSubstr("bodies[1].name: the name \"brick\" is already taken by "
                        "bodies[0]"));
  EXPECT_THAT(scene_error_of(with_body("name", "")),
              HasSubstr("bodies[0].name: expected a non-empty name"));
  EXPECT_THAT(scene_error_of(with_body("name", "a\nb")),
              HasSubstr("bodies[0].name: expected a name without control characters"));
}

TEST(SceneErrors, UnreadableSceneFile) {
  const auto dir = testing::fresh_directory("scene_unreadable");
  EXPECT_THAT(testing::input_error_of([&] { load_scene(dir / "missing.json"); }),
              HasSubstr("missing.json: cannot open the scene file"));
  std::filesystem::remove_all(dir);
}

// ---------------------------------------------------------------------------------------------
// Compilation.

class SceneCompile : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = testing::fresh_directory("scene_compile"); }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  /// Writes `scene` to scenes/scene.json and loads and compiles it.
  CompiledScene compile(const json& scene) {
    const auto file = dir_ / "scenes" / "scene.json";
    std::filesystem::create_directories(file.parent_path());
    std::ofstream(file) << scene.dump(2);
    return compile_scene(load_scene(file));
  }

  std::filesystem::path dir_;
};

TEST_F(SceneCompile, InertiaOnlyBodyHasNoForceTermsAndImportsNoMesh) {
  json scene = with_body("angular_velocity", {0.5, -1, 2});
  const CompiledScene compiled = compile(scene);
  EXPECT_EQ(compiled.meshes_imported, 0u);
  ASSERT_EQ(compiled.bodies.size(), 1u);
  const engine::BodyModel& body = compiled.bodies[0];
  EXPECT_TRUE(body.forces.empty());
  EXPECT_FALSE(body.pivoted);
  EXPECT_EQ(body.mass, 2.0);
  EXPECT_EQ(body.moments, Eigen::Vector3d(1, 2, 3));
  EXPECT_TRUE(body.principal_to_body.coeffs().isApprox(Eigen::Quaterniond::Identity().coeffs()));
  EXPECT_EQ(body.center_offset, Eigen::Vector3d::Zero());
  // L = J w with the identity orientation.
  EXPECT_TRUE(compiled.initial[0].angular_momentum.isApprox(Eigen::Vector3d(0.5, -2, 6), 1e-15));
  EXPECT_EQ(compiled.settings.integrator, engine::IntegratorKind::kRk4);
  EXPECT_EQ(compiled.settings.dt, 0.01);
  EXPECT_EQ(compiled.settings.duration, 1.0);
}

TEST_F(SceneCompile, OnlyTheForceTermsTheSceneAsksFor) {
  json scene = base_scene();
  scene["gravity"] = {0, 0, -9.81};
  scene["bodies"].push_back(
      {{"name", "sprung"},
       {"inertia", {{"principal", {1, 1, 1}}}},
       {"mass", 1},
       {"torque", {0, 0, 0}},
       {"spring", {{"anchor", {0, 0, 1}}, {"attach", {0, 0, 0.1}}, {"stiffness", 100}}}});
  const CompiledScene compiled = compile(scene);
  ASSERT_EQ(compiled.bodies.size(), 2u);
  const engine::BodyModel& plain = compiled.bodies[0];
  ASSERT_EQ(plain.forces.size(), 1u);
  EXPECT_EQ(std::get<engine::Gravity>(plain.forces[0]).acceleration, Eigen::Vector3d(0, 0, -9.81));
  const engine::BodyModel& sprung = compiled.bodies[1];
  EXPECT_EQ(sprung.forces.size(), 3u);
  EXPECT_EQ(count_terms<engine::Gravity>(sprung), 1);
  EXPECT_EQ(count_terms<engine::ConstantTorque>(sprung), 1);  // given, even though zero
  EXPECT_EQ(count_terms<engine::Spring>(sprung), 1);

  // Without gravity in the scene there is no gravity term at all.
  json free = base_scene();
  EXPECT_EQ(count_terms<engine::Gravity>(compile(free).bodies[0]), 0);
}

TEST_F(SceneCompile, UnsortedPrincipalMomentsAreSortedWithAMatchingRotation) {
  // Body x carries 3, y 1, z 2. Whatever the engine's order, the inertia in the body frame and
  // L = R I_body R^T w must come out the same.
  json scene = with_body("inertia", {{"principal", {3, 1, 2}}});
  const Eigen::Quaterniond q_body(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  scene["bodies"][0]["orientation"] = {q_body.w(), q_body.x(), q_body.y(), q_body.z()};
  scene["bodies"][0]["angular_velocity"] = {0.3, -0.2, 1.1};
  const CompiledScene compiled = compile(scene);
  const engine::BodyModel& body = compiled.bodies[0];
  EXPECT_TRUE(body.moments.isApprox(Eigen::Vector3d(1, 2, 3), 1e-15));
  const Eigen::Matrix3d p = body.principal_to_body.toRotationMatrix();
  const Eigen::Matrix3d inertia_body = p * body.moments.asDiagonal() * p.transpose();
  EXPECT_TRUE(inertia_body.isApprox(Eigen::Vector3d(3, 1, 2).asDiagonal().toDenseMatrix(), 1e-14));
  const Eigen::Matrix3d r = q_body.toRotationMatrix();
  const Eigen::Vector3d expected_l =
      r * Eigen::Vector3d(3, 1, 2).asDiagonal() * r.transpose() * Eigen::Vector3d(0.3, -0.2, 1.1);
  EXPECT_TRUE(compiled.initial[0].angular_momentum.isApprox(expected_l, 1e-14));
  // The principal orientation maps back to the user's body orientation.
  const Eigen::Quaterniond back =
      compiled.initial[0].orientation * body.principal_to_body.conjugate();
  EXPECT_NEAR(std::abs(back.dot(q_body)), 1.0, 1e-15);
}

TEST_F(SceneCompile, TensorIsDiagonalised) {
  const Eigen::Matrix3d tensor{{2.0, -0.3, 0.1}, {-0.3, 2.5, 0.2}, {0.1, 0.2, 3.0}};
  json rows = json::array();
  for (int r = 0; r < 3; ++r) rows.push_back({tensor(r, 0), tensor(r, 1), tensor(r, 2)});
  json scene = with_body("inertia", {{"tensor", rows}});
  scene["bodies"][0]["angular_velocity"] = {1, 2, 3};
  const CompiledScene compiled = compile(scene);
  const engine::BodyModel& body = compiled.bodies[0];
  EXPECT_LE(body.moments[0], body.moments[1]);
  EXPECT_LE(body.moments[1], body.moments[2]);
  const Eigen::Matrix3d p = body.principal_to_body.toRotationMatrix();
  EXPECT_TRUE((p * body.moments.asDiagonal() * p.transpose()).isApprox(tensor, 1e-14));
  // Identity body orientation: L = I w.
  EXPECT_TRUE(
      compiled.initial[0].angular_momentum.isApprox(tensor * Eigen::Vector3d(1, 2, 3), 1e-14));
}

TEST_F(SceneCompile, BodyFrameAngularVelocityAndTorque) {
  // A quarter turn about z: body x is world y.
  const double h = std::sqrt(0.5);
  json scene = with_body("orientation", {h, 0, 0, h});
  scene["bodies"][0]["inertia"] = {{"principal", {2, 1, 2.5}}};  // unsorted: P is not identity
  scene["bodies"][0]["angular_velocity"] = {1, 0, 0};
  scene["bodies"][0]["angular_velocity_frame"] = "body";
  scene["bodies"][0]["torque"] = {0, 0.5, 0};
  scene["bodies"][0]["torque_frame"] = "body";
  const CompiledScene compiled = compile(scene);
  const engine::BodyModel& body = compiled.bodies[0];
  // World w = (0, 1, 0) about body x (moment 2): L = (0, 2, 0).
  EXPECT_TRUE(compiled.initial[0].angular_momentum.isApprox(Eigen::Vector3d(0, 2, 0), 1e-14));
  const auto& torque = std::get<engine::ConstantTorque>(body.forces.at(0));
  EXPECT_TRUE(torque.body_frame);
  // In the principal frame; mapped back to the body frame it is the user's (0, 0.5, 0).
  EXPECT_TRUE((body.principal_to_body * torque.torque).isApprox(Eigen::Vector3d(0, 0.5, 0), 1e-15));
}

TEST_F(SceneCompile, PivotUsesTheParallelAxisTheorem) {
  // Principal (1, 2, 3), mass 2, pivot 0.5 below the centre of mass along body z:
  // about the pivot (1 + 0.5, 2 + 0.5, 3).
  const Eigen::Quaterniond q_body(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()));
  json scene = with_body("pivot", {0, 0, -0.5});
  scene["bodies"][0]["position"] = {1, 2, 3};
  scene["bodies"][0]["orientation"] = {q_body.w(), q_body.x(), q_body.y(), q_body.z()};
  scene["bodies"][0]["angular_velocity"] = {0, 0, 4};
  scene["bodies"][0]["spring"] = {
      {"anchor", {0, 0, 9}}, {"attach", {0, 0, 0.25}}, {"stiffness", 1}};
  const CompiledScene compiled = compile(scene);
  const engine::BodyModel& body = compiled.bodies[0];
  EXPECT_TRUE(body.pivoted);
  EXPECT_TRUE(body.moments.isApprox(Eigen::Vector3d(1.5, 2.5, 3), 1e-15));
  EXPECT_TRUE(body.center_offset.isApprox(Eigen::Vector3d(0, 0, 0.5), 1e-15));
  const Eigen::Vector3d pivot_world =
      Eigen::Vector3d(1, 2, 3) + q_body * Eigen::Vector3d(0, 0, -0.5);
  EXPECT_TRUE(body.pivot.isApprox(pivot_world, 1e-15));
  // The spring's attach point is relative to the pivot.
  EXPECT_TRUE(std::get<engine::Spring>(body.forces.at(0))
                  .attach.isApprox(Eigen::Vector3d(0, 0, 0.75), 1e-15));
  // The centre of mass stays where the scene put it and moves with w x (x - pivot).
  const engine::BodyState& state = compiled.initial[0];
  EXPECT_TRUE(state.position.isApprox(Eigen::Vector3d(1, 2, 3), 1e-14));
  const Eigen::Vector3d w(0, 0, 4);
  EXPECT_TRUE(state.velocity.isApprox(w.cross(state.position - pivot_world), 1e-14));
  const Eigen::Matrix3d r = q_body.toRotationMatrix();
  const Eigen::Vector3d expected_l =
      r * Eigen::Vector3d(1.5, 2.5, 3).asDiagonal() * r.transpose() * w;
  EXPECT_TRUE(state.angular_momentum.isApprox(expected_l, 1e-14));
}

TEST_F(SceneCompile, MeshBodyUsesTheMeshMassProperties) {
  // A 0.25 x 0.5 x 0.75 box centred at (1, 2, 3), given a total mass of 6 kg (sizes exact in
  // single precision, which the importer may use).
  write_box_obj(dir_ / "meshes" / "box.obj", {0.25, 0.5, 0.75}, {1, 2, 3});
  json scene = base_scene();
  scene["bodies"][0] = {{"name", "box"},
                        {"mesh", "../meshes/box.obj"},
                        {"mass", 6.0},
                        {"angular_velocity", {0, 0, 1}}};
  const CompiledScene compiled = compile(scene);
  EXPECT_EQ(compiled.meshes_imported, 1u);
  const engine::BodyModel& body = compiled.bodies[0];
  EXPECT_NEAR(body.mass, 6.0, 1e-12);
  const Eigen::Vector3d expected =
      6.0 / 12.0 * Eigen::Vector3d(0.25 + 0.5625, 0.0625 + 0.5625, 0.0625 + 0.25);
  const Eigen::Matrix3d p = body.principal_to_body.toRotationMatrix();
  EXPECT_TRUE((p * body.moments.asDiagonal() * p.transpose())
                  .isApprox(expected.asDiagonal().toDenseMatrix(), 1e-12));
  EXPECT_NEAR(compiled.initial[0].angular_momentum.z(), expected.z(), 1e-12);

  // Density instead of mass, and a scale: the same box in millimetres.
  write_box_obj(dir_ / "meshes" / "box_mm.obj", {250, 500, 750}, {0, 0, 0});
  scene["bodies"][0] = {{"mesh", "../meshes/box_mm.obj"}, {"density", 500}, {"scale", 0.001}};
  EXPECT_NEAR(compile(scene).bodies[0].mass, 500 * 0.09375, 1e-9);
}

TEST_F(SceneCompile, OverlappingPartsOfAMeshNeedAllowOverlap) {
  // Two boxes in one file, the second moved half a box along each axis: they share an eighth.
  const auto file = dir_ / "meshes" / "two.obj";
  write_box_obj(file, {1, 1, 1}, {0, 0, 0});
  std::ifstream in(file);
  const std::string first((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  write_box_obj(dir_ / "meshes" / "moved.obj", {1, 1, 1}, {0.5, 0.5, 0.5});
  std::ifstream moved_in(dir_ / "meshes" / "moved.obj");
  std::string second;
  for (std::string line; std::getline(moved_in, line);) {
    if (line[0] == 'f') {
      std::istringstream face(line.substr(2));
      int a = 0, b = 0, c = 0;
      face >> a >> b >> c;
      line =
          "f " + std::to_string(a + 8) + " " + std::to_string(b + 8) + " " + std::to_string(c + 8);
    }
    second += line + "\n";
  }
  std::ofstream(file) << first << second;
  json scene = base_scene();
  scene["bodies"][0] = {{"mesh", "../meshes/two.obj"}, {"density", 1.0}, {"overlap", "refuse"}};
  EXPECT_THAT(testing::input_error_of([&] { compile(scene); }),
              AllOf(HasSubstr("scenes/scene.json: bodies[0].mesh: "),
                    HasSubstr("parts 1 and 2 of 2 overlap (their surfaces cross)")));
  scene["bodies"][0].erase("overlap");
  scene["bodies"][0]["allow_overlap"] = true;
  EXPECT_NEAR(compile(scene).bodies[0].mass, 2.0, 1e-9);  // both boxes, as warned
}

TEST_F(SceneCompile, MeshErrorsArePrefixedWithTheJsonPath) {
  json scene = base_scene();
  scene["bodies"][0] = {{"mesh", "../meshes/nowhere.obj"}, {"mass", 1.0}};
  const std::string message = testing::input_error_of([&] { compile(scene); });
  EXPECT_THAT(message, HasSubstr("scenes/scene.json: bodies[0].mesh: "));
  EXPECT_THAT(message, HasSubstr("nowhere.obj"));
}

}  // namespace
}  // namespace tumble::app
