// JsonField: typed, range-checked access to JSON values, with file and JSON path in every
// message; number_text and describe for the "got ..." half of those messages.
#include "app/scene/json_field.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "support/input_error.hpp"

namespace tumble::app {
namespace {

using nlohmann::json;
using testing::input_error_of;

const std::string kJsonFieldFile = "scene.json";

TEST(NumberText, ShortestTextThatReadsBack) {
  EXPECT_EQ(number_text(0.1), "0.1");
  EXPECT_EQ(number_text(2.0), "2");
  EXPECT_EQ(number_text(-0.5), "-0.5");
  EXPECT_EQ(number_text(1e300), "1e+300");
  EXPECT_EQ(number_text(0.1 + 0.2), "0.30000000000000004");
  EXPECT_EQ(std::stod(number_text(1.0 / 3.0)), 1.0 / 3.0);
}

TEST(NumberText, NonFiniteValues) {
  EXPECT_EQ(number_text(std::numeric_limits<double>::infinity()), "inf");
  EXPECT_EQ(number_text(-std::numeric_limits<double>::infinity()), "-inf");
  EXPECT_EQ(number_text(std::nan("")), "nan");
}

TEST(Describe, EveryKindOfValue) {
  EXPECT_EQ(describe(json(nullptr)), "null");
  EXPECT_EQ(describe(json(true)), "true");
  EXPECT_EQ(describe(json(false)), "false");
  EXPECT_EQ(describe(json("abc")), "the string \"abc\"");
  EXPECT_EQ(describe(json::array({1, 2, 3})), "an array of 3");
  EXPECT_EQ(describe(json::array()), "an array of 0");
  EXPECT_EQ(describe(json::object()), "an object");
  EXPECT_EQ(describe(json(-4)), "-4");
  EXPECT_EQ(describe(json(7u)), "7");
  EXPECT_EQ(describe(json(2.5)), "2.5");
}

TEST(JsonField, FailNamesFileAndPathOrTheTopLevel) {
  const json value = 1;
  EXPECT_EQ(input_error_of([&] { JsonField(value, "bodies[0].mass", kJsonFieldFile).fail("bad"); }),
            "scene.json: bodies[0].mass: bad");
  EXPECT_EQ(input_error_of([&] { JsonField(value, "", kJsonFieldFile).fail("bad"); }),
            "scene.json: (top level): bad");
}

TEST(JsonField, FindAndRequireBuildChildPaths) {
  const json doc = json::parse(R"({"render": {"camera": {"fov": 45}}})");
  const JsonField top(doc, "", kJsonFieldFile);
  const auto render = top.find("render");
  ASSERT_TRUE(render.has_value());
  EXPECT_EQ(render->path(), "render");
  const JsonField fov = render->require("camera", "an object").require("fov", "degrees");
  EXPECT_EQ(fov.path(), "render.camera.fov");
  EXPECT_EQ(fov.number(), 45.0);
  EXPECT_FALSE(top.find("bodies").has_value());
}

TEST(JsonField, RequireOfAMissingKeySaysWhatWasExpected) {
  const json doc = json::parse(R"({"render": {}})");
  const JsonField render = JsonField(doc, "", kJsonFieldFile).require("render", "an object");
  EXPECT_EQ(input_error_of([&] { render.require("fps", "frames per second, e.g. 30"); }),
            "scene.json: render.fps: missing; expected frames per second, e.g. 30");
  EXPECT_EQ(
      input_error_of([&] { JsonField(doc, "", kJsonFieldFile).require("bodies", "an array"); }),
      "scene.json: bodies: missing; expected an array");
}

TEST(JsonField, ElementPathsIndexArrays) {
  const json doc = json::parse(R"({"bodies": [{"mass": 1}, {"mass": -2}]})");
  const JsonField bodies = JsonField(doc, "", kJsonFieldFile).require("bodies", "an array");
  const JsonField mass = bodies.element(1).require("mass", "kg");
  EXPECT_EQ(mass.path(), "bodies[1].mass");
  EXPECT_EQ(input_error_of([&] { mass.positive(); }),
            "scene.json: bodies[1].mass: expected a positive number, got -2");
}

TEST(JsonField, ExpectObjectListsTheAllowedKeys) {
  const json doc = json::parse(R"({"body": {"mass": 1, "colour": "red"}})");
  const JsonField body = JsonField(doc, "", kJsonFieldFile).require("body", "an object");
  EXPECT_NO_THROW(body.expect_object({"mass", "colour", "name"}));
  EXPECT_EQ(input_error_of([&] {
              body.expect_object({"mass", "color"});
            }),
            "scene.json: body.colour: unknown key; expected one of: mass, color");
  const json number = 3;
  EXPECT_EQ(
      input_error_of([&] { JsonField(number, "body", kJsonFieldFile).expect_object({"mass"}); }),
      "scene.json: body: expected an object, got 3");
}

TEST(JsonField, ExpectArrayChecksTypeAndSize) {
  const json three = json::array({1, 2, 3});
  EXPECT_NO_THROW(JsonField(three, "v", kJsonFieldFile).expect_array(3, "three numbers"));
  EXPECT_EQ(
      input_error_of([&] { JsonField(three, "v", kJsonFieldFile).expect_array(2, "a pair"); }),
      "scene.json: v: expected a pair, got an array of 3");
  const json text = "xyz";
  EXPECT_EQ(input_error_of([&] { JsonField(text, "v", kJsonFieldFile).expect_array(3, "three"); }),
            "scene.json: v: expected three, got the string \"xyz\"");
}

TEST(JsonField, NumberAcceptsEveryJsonNumberType) {
  EXPECT_EQ(JsonField(json(-3), "n", kJsonFieldFile).number(), -3.0);
  EXPECT_EQ(JsonField(json(5u), "n", kJsonFieldFile).number(), 5.0);
  EXPECT_EQ(JsonField(json(0.25), "n", kJsonFieldFile).number(), 0.25);
}

TEST(JsonField, NumberRefusesOtherTypesAndNonFiniteValues) {
  EXPECT_EQ(input_error_of([&] { JsonField(json("1"), "dt", kJsonFieldFile).number(); }),
            "scene.json: dt: expected a number, got the string \"1\"");
  EXPECT_EQ(input_error_of([&] { JsonField(json(nullptr), "dt", kJsonFieldFile).number(); }),
            "scene.json: dt: expected a number, got null");
  EXPECT_EQ(input_error_of([&] { JsonField(json(true), "dt", kJsonFieldFile).number(); }),
            "scene.json: dt: expected a number, got true");
  const json infinite = std::numeric_limits<double>::infinity();
  EXPECT_EQ(input_error_of([&] { JsonField(infinite, "dt", kJsonFieldFile).number(); }),
            "scene.json: dt: expected a finite number, got inf (JSON numbers beyond +-1.8e308 "
            "read as infinity)");
}

TEST(JsonField, PositiveAndNonNegativeBoundaries) {
  EXPECT_EQ(JsonField(json(1e-300), "x", kJsonFieldFile).positive(), 1e-300);
  EXPECT_EQ(input_error_of([&] { JsonField(json(0), "x", kJsonFieldFile).positive(); }),
            "scene.json: x: expected a positive number, got 0");
  EXPECT_EQ(JsonField(json(0), "x", kJsonFieldFile).non_negative(), 0.0);
  EXPECT_EQ(input_error_of([&] { JsonField(json(-1e-9), "x", kJsonFieldFile).non_negative(); }),
            "scene.json: x: expected a number >= 0, got -1e-09");
}

TEST(JsonField, InRangeIncludesBothEnds) {
  EXPECT_EQ(JsonField(json(0.0), "a", kJsonFieldFile).in_range(0.0, 1.0), 0.0);
  EXPECT_EQ(JsonField(json(1.0), "a", kJsonFieldFile).in_range(0.0, 1.0), 1.0);
  EXPECT_EQ(input_error_of([&] { JsonField(json(1.5), "a", kJsonFieldFile).in_range(0.0, 1.0); }),
            "scene.json: a: expected a number from 0 to 1, got 1.5");
  EXPECT_EQ(input_error_of([&] { JsonField(json(-0.25), "a", kJsonFieldFile).in_range(0.0, 1.0); }),
            "scene.json: a: expected a number from 0 to 1, got -0.25");
}

TEST(JsonField, IntegerWantsAWholeNumberInRange) {
  EXPECT_EQ(JsonField(json(3), "n", kJsonFieldFile).integer(1, 10), 3);
  EXPECT_EQ(JsonField(json(10.0), "n", kJsonFieldFile).integer(1, 10), 10);
  EXPECT_EQ(JsonField(json(1), "n", kJsonFieldFile).integer(1, 10), 1);
  EXPECT_EQ(input_error_of([&] { JsonField(json(2.5), "n", kJsonFieldFile).integer(1, 10); }),
            "scene.json: n: expected a whole number from 1 to 10, got 2.5");
  EXPECT_EQ(input_error_of([&] { JsonField(json(11), "n", kJsonFieldFile).integer(1, 10); }),
            "scene.json: n: expected a whole number from 1 to 10, got 11");
  EXPECT_EQ(input_error_of([&] { JsonField(json(0), "n", kJsonFieldFile).integer(1, 10); }),
            "scene.json: n: expected a whole number from 1 to 10, got 0");
}

TEST(JsonField, BooleanAndString) {
  EXPECT_TRUE(JsonField(json(true), "b", kJsonFieldFile).boolean());
  EXPECT_FALSE(JsonField(json(false), "b", kJsonFieldFile).boolean());
  EXPECT_EQ(input_error_of([&] { JsonField(json(1), "b", kJsonFieldFile).boolean(); }),
            "scene.json: b: expected true or false, got 1");
  EXPECT_EQ(JsonField(json("rk4"), "s", kJsonFieldFile).string(), "rk4");
  EXPECT_EQ(input_error_of([&] { JsonField(json::array(), "s", kJsonFieldFile).string(); }),
            "scene.json: s: expected a string, got an array of 0");
}

TEST(JsonField, Vector3ReadsThreeFiniteNumbers) {
  const json v = json::array({1, -2.5, 3e3});
  EXPECT_EQ(JsonField(v, "w", kJsonFieldFile).vector3(), Eigen::Vector3d(1, -2.5, 3000));
  const json two = json::array({1, 2});
  EXPECT_EQ(input_error_of([&] { JsonField(two, "w", kJsonFieldFile).vector3(); }),
            "scene.json: w: expected an array of 3 finite numbers [x, y, z], got an array of 2");
  const json text = json::array({1, "2", 3});
  EXPECT_EQ(input_error_of([&] { JsonField(text, "w", kJsonFieldFile).vector3(); }),
            "scene.json: w[1]: expected a number, got the string \"2\"");
}

}  // namespace
}  // namespace tumble::app
