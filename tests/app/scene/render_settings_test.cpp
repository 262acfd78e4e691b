#include "app/scene/render_settings.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <limits>
#include <nlohmann/json.hpp>

#include "base/errors.hpp"
#include "support/input_error.hpp"

namespace tumble::app {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;

const std::vector<std::string> kBodies = {"handle", "coin"};

RenderSettings parse(const std::string& text) {
  return parse_render_settings(json::parse(text), "scene.json", kBodies);
}

/// The message of the InputError that parsing `text` throws (a failure if it does not).
std::string render_settings_error_of(const std::string& text) {
  return testing::input_error_of([&] { parse(text); }, text);
}

TEST(RenderSettings, EmptyObjectGivesTheDefaults) {
  const RenderSettings s = parse("{}");
  EXPECT_EQ(s.width, 1280);
  EXPECT_EQ(s.height, 720);
  EXPECT_EQ(s.fps, 30.0);
  EXPECT_EQ(s.time_scale, 1.0);
  EXPECT_EQ(s.antialiasing, (Antialiasing{Antialiasing::Mode::kFxaa, 1}));  // FXAA by default
  EXPECT_EQ(s.camera.mode, CameraSettings::Mode::kFixed);
  EXPECT_FALSE(s.camera.eye.has_value());
  EXPECT_FALSE(s.camera.target.has_value());
  EXPECT_FALSE(s.camera.distance.has_value());
  EXPECT_TRUE(s.show.bodies);
  EXPECT_TRUE(s.show.angular_velocity);
  EXPECT_TRUE(s.show.angular_momentum);
  EXPECT_TRUE(s.show.overlay);
  EXPECT_FALSE(s.show.ground);
  EXPECT_TRUE(s.show.trails.empty());
}

TEST(RenderSettings, ReadsEveryKey) {
  const RenderSettings s = parse(R"({
    "size": [640, 360], "fps": 60, "time_scale": 0.25, "antialiasing": 4,
    "camera": {"mode": "follow", "eye": [1, 2, 3], "target": [0, 0, 0.5], "fov": 55,
               "distance": 7.5, "azimuth": 30, "elevation": -10, "orbit_period": 12,
               "follow": "coin"},
    "show": {"bodies": false, "body_axes": true, "principal_axes": true,
             "angular_velocity": false, "angular_momentum": false, "herpolhode": true,
             "polhode": true, "inertia_ellipsoid": true, "ground": true, "overlay": false,
             "trails": [{"body": "coin", "point": [0.1, 0, 0], "seconds": 2.5},
                        {"body": "handle"}]}
  })");
  EXPECT_EQ(s.width, 640);
  EXPECT_EQ(s.height, 360);
  EXPECT_EQ(s.fps, 60.0);
  EXPECT_EQ(s.time_scale, 0.25);
  EXPECT_EQ(s.antialiasing, (Antialiasing{Antialiasing::Mode::kMultisample, 4}));
  EXPECT_EQ(s.camera.mode, CameraSettings::Mode::kFollow);
  EXPECT_EQ(*s.camera.eye, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(*s.camera.target, Eigen::Vector3d(0, 0, 0.5));
  EXPECT_EQ(s.camera.fov_deg, 55.0);
  EXPECT_EQ(*s.camera.distance, 7.5);
  EXPECT_EQ(s.camera.azimuth_deg, 30.0);
  EXPECT_EQ(s.camera.elevation_deg, -10.0);
  EXPECT_EQ(s.camera.orbit_period, 12.0);
  EXPECT_EQ(s.camera.follow_body, 1u);
  EXPECT_FALSE(s.show.bodies);
  EXPECT_TRUE(s.show.body_axes);
  EXPECT_TRUE(s.show.principal_axes);
  EXPECT_FALSE(s.show.angular_velocity);
  EXPECT_FALSE(s.show.angular_momentum);
  EXPECT_TRUE(s.show.herpolhode);
  EXPECT_TRUE(s.show.polhode);
  EXPECT_TRUE(s.show.inertia_ellipsoid);
  EXPECT_TRUE(s.show.ground);
  EXPECT_FALSE(s.show.overlay);
  ASSERT_EQ(s.show.trails.size(), 2u);
  EXPECT_EQ(s.show.trails[0].body, 1u);
  EXPECT_EQ(s.show.trails[0].point, Eigen::Vector3d(0.1, 0, 0));
  EXPECT_EQ(s.show.trails[0].seconds, 2.5);
  EXPECT_EQ(s.show.trails[1].body, 0u);
  EXPECT_EQ(s.show.trails[1].point, Eigen::Vector3d::Zero());
  EXPECT_EQ(s.show.trails[1].seconds, 5.0);
}

TEST(RenderSettings, CameraModes) {
  EXPECT_EQ(parse(R"({"camera": {"mode": "fixed"}})").camera.mode, CameraSettings::Mode::kFixed);
  EXPECT_EQ(parse(R"({"camera": {"mode": "orbit"}})").camera.mode, CameraSettings::Mode::kOrbit);
  EXPECT_EQ(parse(R"({"camera": {"mode": "follow"}})").camera.mode, CameraSettings::Mode::kFollow);
}

TEST(RenderSettings, TrailBodyMayBeOmittedWithOneBody) {
  const RenderSettings s = parse_render_settings(
      json::parse(R"({"show": {"trails": [{"point": [0, 0, 1]}]}})"), "a.json", {"only"});
  ASSERT_EQ(s.show.trails.size(), 1u);
  EXPECT_EQ(s.show.trails[0].body, 0u);
}

struct BadCase {
  const char* json;
  const char* message;
};

class RenderSettingsError : public ::testing::TestWithParam<BadCase> {};

TEST_P(RenderSettingsError, NamesThePathAndWhatWasExpected) {
  const std::string message = render_settings_error_of(GetParam().json);
  EXPECT_THAT(message, HasSubstr(GetParam().message)) << GetParam().json;
  EXPECT_THAT(message, HasSubstr("scene.json: render")) << GetParam().json;
}

INSTANTIATE_TEST_SUITE_P(
    AllKeys, RenderSettingsError,
    ::testing::Values(
        BadCase{R"([])", "render: expected an object, got an array of 0"},
        BadCase{R"({"colour": 1})", "render.colour: unknown key; expected one of: size, fps"},
        BadCase{R"({"size": 3})", "render.size: expected an image size [width, height]"},
        BadCase{R"({"size": [640]})", "render.size: expected an image size"},
        BadCase{R"({"size": [641, 480]})", "render.size[0]: expected an even number of pixels"},
        BadCase{R"({"size": [640, 481]})", "render.size[1]: expected an even number of pixels"},
        BadCase{R"({"size": [0, 480]})", "render.size[0]: expected a whole number from 2 to 8192"},
        BadCase{R"({"size": [8194, 480]})", "render.size[0]: expected a whole number from 2"},
        BadCase{R"({"size": [640.5, 480]})", "render.size[0]: expected a whole number"},
        BadCase{R"({"size": ["640", 480]})", "render.size[0]: expected a number, got the string"},
        BadCase{R"({"fps": 0})", "render.fps: expected a positive number, got 0"},
        BadCase{R"({"fps": 241})", "render.fps: expected at most 240 frames per second, got 241"},
        BadCase{R"({"fps": "30"})", "render.fps: expected a number, got the string \"30\""},
        BadCase{R"({"time_scale": -1})", "render.time_scale: expected a positive number, got -1"},
        BadCase{R"({"antialiasing": 0})",
                "render.antialiasing: expected off, fxaa or multisampling samples per pixel from 2 "
                "to 16 (1: off), got 0"},
        BadCase{R"({"antialiasing": 17})", "render.antialiasing: expected off, fxaa or"},
        BadCase{R"({"antialiasing": 2.5})", "render.antialiasing: expected off, fxaa or"},
        BadCase{R"({"antialiasing": "smaa"})",
                "render.antialiasing: expected off, fxaa or multisampling samples per pixel from 2 "
                "to 16 (1: off), got \"smaa\""},
        BadCase{R"({"antialiasing": "4"})", "render.antialiasing: expected off, fxaa or"},
        BadCase{R"({"antialiasing": true})", "render.antialiasing: expected off, fxaa or"},
        BadCase{R"({"camera": 1})", "render.camera: expected an object, got 1"},
        BadCase{R"({"camera": {"zoom": 1}})",
                "render.camera.zoom: unknown key; expected one of: mode"},
        BadCase{R"({"camera": {"mode": "x"}})",
                "render.camera.mode: expected one of fixed, orbit, follow, got \"x\""},
        BadCase{R"({"camera": {"mode": 3}})", "render.camera.mode: expected a string, got 3"},
        BadCase{R"({"camera": {"eye": [1, 2]}})",
                "render.camera.eye: expected an array of 3 finite numbers [x, y, z], got an array "
                "of 2"},
        BadCase{R"({"camera": {"eye": [1, 2, null]}})",
                "render.camera.eye[2]: expected a number, got null"},
        BadCase{R"({"camera": {"target": "origin"}})",
                "render.camera.target: expected an array of 3"},
        BadCase{R"({"camera": {"eye": [1, 1, 1], "target": [1, 1, 1]}})",
                "render.camera.eye: the eye must differ from the target"},
        BadCase{R"({"camera": {"fov": 0.5}})",
                "render.camera.fov: expected a number from 1 to 170, got 0.5"},
        BadCase{R"({"camera": {"fov": 171}})",
                "render.camera.fov: expected a number from 1 to 170, got 171"},
        BadCase{R"({"camera": {"distance": 0}})",
                "render.camera.distance: expected a positive number, got 0"},
        BadCase{R"({"camera": {"azimuth": true}})",
                "render.camera.azimuth: expected a number, got true"},
        BadCase{R"({"camera": {"elevation": 90}})",
                "render.camera.elevation: expected a number from -89 to 89, got 90"},
        BadCase{R"({"camera": {"orbit_period": -3}})",
                "render.camera.orbit_period: expected a positive number, got -3"},
        BadCase{R"({"camera": {"follow": "ghost"}})",
                "render.camera.follow: no body is named \"ghost\"; the bodies are: handle, coin"},
        BadCase{R"({"camera": {"follow": 0}})", "render.camera.follow: expected a string, got 0"},
        BadCase{R"({"show": []})", "render.show: expected an object, got an array of 0"},
        BadCase{R"({"show": {"axes": true}})",
                "render.show.axes: unknown key; expected one of: bodies"},
        BadCase{R"({"show": {"bodies": 1}})", "render.show.bodies: expected true or false, got 1"},
        BadCase{R"({"show": {"body_axes": "yes"}})",
                "render.show.body_axes: expected true or false"},
        BadCase{R"({"show": {"principal_axes": null}})",
                "render.show.principal_axes: expected true or false, got null"},
        BadCase{R"({"show": {"angular_velocity": 0}})",
                "render.show.angular_velocity: expected true or false"},
        BadCase{R"({"show": {"angular_momentum": 0}})",
                "render.show.angular_momentum: expected true or false"},
        BadCase{R"({"show": {"herpolhode": 0}})", "render.show.herpolhode: expected true or false"},
        BadCase{R"({"show": {"polhode": 0}})", "render.show.polhode: expected true or false"},
        BadCase{R"({"show": {"inertia_ellipsoid": 0}})",
                "render.show.inertia_ellipsoid: expected true or false"},
        BadCase{R"({"show": {"ground": 0}})", "render.show.ground: expected true or false"},
        BadCase{R"({"show": {"overlay": 0}})", "render.show.overlay: expected true or false"},
        BadCase{R"({"show": {"trails": {}}})", "render.show.trails: expected an array of trails"},
        BadCase{R"({"show": {"trails": [1]}})", "render.show.trails[0]: expected an object, got 1"},
        BadCase{R"({"show": {"trails": [{"body": "coin", "colour": 1}]}})",
                "render.show.trails[0].colour: unknown key; expected one of: body, point, seconds"},
        BadCase{R"({"show": {"trails": [{"point": [0, 0, 0]}]}})",
                "render.show.trails[0]: missing \"body\": name the body the trail follows"},
        BadCase{R"({"show": {"trails": [{"body": "cone"}]}})",
                "render.show.trails[0].body: no body is named \"cone\""},
        BadCase{R"({"show": {"trails": [{"body": "coin", "point": [0, 0]}]}})",
                "render.show.trails[0].point: expected an array of 3 finite numbers"},
        BadCase{R"({"show": {"trails": [{"body": "coin", "seconds": 0}]}})",
                "render.show.trails[0].seconds: expected a positive number, got 0"}));

TEST(RenderSettings, NonFiniteNumbersAreRefused) {
  // JSON text has no infinity, but a json value built in code (or by a lenient reader) may.
  json render;
  render["time_scale"] = std::numeric_limits<double>::infinity();
  EXPECT_THAT(
      testing::input_error_of([&] { parse_render_settings(render, "scene.json", kBodies); }),
      HasSubstr("render.time_scale: expected a finite number, got inf"));
}

TEST(RenderSettings, AntialiasingIsOffFxaaOrSamples) {
  using Mode = Antialiasing::Mode;
  EXPECT_EQ(parse(R"({"antialiasing": "off"})").antialiasing, (Antialiasing{Mode::kOff, 1}));
  EXPECT_EQ(parse(R"({"antialiasing": "fxaa"})").antialiasing, (Antialiasing{Mode::kFxaa, 1}));
  EXPECT_EQ(parse(R"({"antialiasing": 1})").antialiasing, (Antialiasing{Mode::kOff, 1}));
  EXPECT_EQ(parse(R"({"antialiasing": 16})").antialiasing, (Antialiasing{Mode::kMultisample, 16}));
  // --aa's text: the same values.
  EXPECT_EQ(antialiasing_from_text("off"), (Antialiasing{Mode::kOff, 1}));
  EXPECT_EQ(antialiasing_from_text("fxaa"), (Antialiasing{Mode::kFxaa, 1}));
  EXPECT_EQ(antialiasing_from_text("1"), (Antialiasing{Mode::kOff, 1}));
  EXPECT_EQ(antialiasing_from_text("2"), (Antialiasing{Mode::kMultisample, 2}));
  for (const char* bad : {"", "0", "17", "-4", "4x", " 4", "FXAA", "msaa"}) {
    EXPECT_FALSE(antialiasing_from_text(bad).has_value()) << bad;
  }
}

}  // namespace
}  // namespace tumble::app
