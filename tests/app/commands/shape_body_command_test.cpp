// Shape bodies end to end: `tumble simulate` moves a box shape exactly as the same box given by
// its inertia, and `tumble render` draws a shape's true geometry (a box shape looks like the
// equivalent box an inertia body is drawn as; a cylinder does not).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include <nlohmann/json.hpp>

#include "engine/mass/primitive_shapes.hpp"
#include "media/png_io.hpp"
#include "support/command_test.hpp"
#include "support/image_compare.hpp"
#include "support/run_command.hpp"
#include "support/scene_builder.hpp"

namespace tumble::app {
namespace {

using nlohmann::json;
using tumble::testing::read_text;
using tumble::testing::run_command;
using tumble::testing::tumble_executable;

/// A tumbling body under gravity and a body-frame torque, given by `solid` (its shape or its
/// inertia) and a mass of 2.5 kg.
json tumbling(const json& solid) {
  testing::BodyBuilder body("solid");
  body.erase("inertia")
      .mass(2.5)
      .position({0.1, 0.2, 0.3})
      .velocity({0.5, 0.0, 2.0})
      .orientation(0.9, 0.1, 0.3, -0.2)
      .angular_velocity({0.3, 4.0, 0.2}, "body")
      .torque({0.0, 0.0, 0.05})
      .set("torque_frame", "body");
  for (const auto& [key, value] : solid.items()) body.set(key, value);
  return testing::SceneBuilder()
      .duration(0.6)
      .dt(0.002)
      .integrator("rk4")
      .set("gravity", {0.0, 0.0, -9.81})
      .body(body)
      .json();
}

/// The box's principal moments from the engine, written as the JSON numbers that read back as
/// the same doubles.
json box_inertia(const Eigen::Vector3d& size, double mass) {
  const Eigen::Matrix3d inertia = engine::mass_properties_of_mass(engine::Box{size}, mass).inertia;
  return {{"principal", {inertia(0, 0), inertia(1, 1), inertia(2, 2)}}};
}

class ShapeBodyCommand : public testing::CommandTest {};

TEST_F(ShapeBodyCommand, ABoxShapeMovesExactlyAsTheSameBoxGivenByItsInertia) {
  const Eigen::Vector3d size(0.2, 0.5, 0.9);
  const std::string shape =
      write_scene(tumbling({{"shape", {{"box", {0.2, 0.5, 0.9}}}}}), "a.json");
  const std::string inertia =
      write_scene(tumbling({{"inertia", box_inertia(size, 2.5)}}), "b.json");
  const auto a =
      run_command(tumble_executable() + " simulate " + shape + " --csv " + path("a.csv"));
  ASSERT_EQ(a.status, 0) << a.err;
  const auto b =
      run_command(tumble_executable() + " simulate " + inertia + " --csv " + path("b.csv"));
  ASSERT_EQ(b.status, 0) << b.err;
  const std::string csv = read_text(dir_ / "a.csv");
  EXPECT_GT(csv.size(), 300u * 100u);  // 301 rows of numbers
  EXPECT_EQ(csv, read_text(dir_ / "b.csv"));
}

TEST_F(ShapeBodyCommand, ABadShapeIsOneLineNamingTheFileAndFieldWithExitOne) {
  const std::string scene =
      write_scene(tumbling({{"shape", {{"cylinder", {{"radius", -1}, {"length", 1}}}}}}));
  const auto result = run_command(tumble_executable() + " simulate " + scene);
  EXPECT_EQ(result.status, 1);
  EXPECT_THAT(result.err, ::testing::HasSubstr(scene + ": bodies[0].shape.cylinder.radius: "
                                                       "expected a positive number, got -1\n"));
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
}

TEST_F(ShapeBodyCommand, RenderDrawsTheShapesTrueGeometry) {
  const auto frame = [&](const json& solid, const std::string& name) {
    json scene = tumbling(solid);
    scene["duration"] = 0.1;
    const std::string file = write_scene(scene, name + ".json");
    const auto result =
        run_command(tumble_executable() + " render " + file + " -o " + path(name + "/") +
                    " --size 160x96 --frames 0:1 --no-overlay -q");
    EXPECT_EQ(result.status, 0) << result.err;
    return media::read_png(dir_ / name / "frame_000000.png");
  };
  const Eigen::Vector3d size(0.2, 0.5, 0.9);
  const tumble::Image box = frame({{"shape", {{"box", {0.2, 0.5, 0.9}}}}}, "box");
  const tumble::Image inertia = frame({{"inertia", box_inertia(size, 2.5)}}, "inertia");
  // Same box, drawn from the shape or rebuilt from the moments: rounding apart, the same image.
  EXPECT_LT(testing::fraction_differing(box, inertia, 8), 0.002);
  // A cylinder is drawn as a cylinder, not as the box an inertia with its moments gets.
  const engine::Shape cylinder = engine::Cylinder{0.3, 0.9};
  const Eigen::Matrix3d moments = engine::mass_properties_of_mass(cylinder, 2.5).inertia;
  const tumble::Image drawn =
      frame({{"shape", {{"cylinder", {{"radius", 0.3}, {"length", 0.9}}}}}}, "cylinder");
  const tumble::Image as_box = frame(
      {{"inertia", {{"principal", {moments(0, 0), moments(1, 1), moments(2, 2)}}}}}, "as_box");
  EXPECT_GT(testing::fraction_differing(drawn, as_box, 8), 0.01);
}

}  // namespace
}  // namespace tumble::app
