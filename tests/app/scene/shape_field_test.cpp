// Primitive shapes in scene files: every kind parses to the engine's Shape, every mistake is a
// one-line error naming the file and the JSON path, and a shape body compiles to the closed-form
// inertia with its tessellation kept for drawing (engine/PHYSICS.md §9).
#include "app/scene/shape_field.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <variant>

#include <nlohmann/json.hpp>

#include "app/scene/scene.hpp"
#include "base/errors.hpp"
#include "support/input_error.hpp"
#include "support/scene_builder.hpp"

namespace tumble::app {
namespace {

using nlohmann::json;
using ::testing::AllOf;
using ::testing::HasSubstr;

const std::filesystem::path kShapeFieldFile = "scenes/shapes.json";

/// A one-body scene whose body has `shape` and the given matter instead of an inertia.
json shape_scene(const json& shape, const std::string& matter = "mass", double amount = 3.0) {
  json scene =
      testing::SceneBuilder().duration(1.0).dt(0.01).body(testing::BodyBuilder("solid")).json();
  json& body = scene["bodies"][0];
  body.erase("inertia");
  body.erase("mass");
  body["shape"] = shape;
  body[matter] = amount;
  return scene;
}

SceneDescription parse(const json& scene) {
  return parse_scene(scene.dump(), kShapeFieldFile);
}

std::string shape_field_error_of(const json& scene) {
  return testing::input_error_of([&] { parse(scene); }, scene.dump());
}

TEST(SceneShapes, EveryKindParses) {
  const auto shape_of = [](const json& shape) {
    return *parse(shape_scene(shape)).bodies[0].shape;
  };
  const engine::Shape box = shape_of({{"box", {0.1, 0.2, 0.3}}});
  ASSERT_TRUE(std::holds_alternative<engine::Box>(box));
  EXPECT_EQ(std::get<engine::Box>(box).size, Eigen::Vector3d(0.1, 0.2, 0.3));
  const engine::Shape sphere = shape_of({{"sphere", {{"radius", 0.5}}}});
  EXPECT_EQ(std::get<engine::Sphere>(sphere).radius, 0.5);
  const engine::Shape cylinder = shape_of({{"cylinder", {{"radius", 0.5}, {"length", 2}}}});
  EXPECT_EQ(std::get<engine::Cylinder>(cylinder).radius, 0.5);
  EXPECT_EQ(std::get<engine::Cylinder>(cylinder).length, 2.0);
  const engine::Shape capsule = shape_of({{"capsule", {{"length", 1.5}, {"radius", 0.25}}}});
  EXPECT_EQ(std::get<engine::Capsule>(capsule).radius, 0.25);
  EXPECT_EQ(std::get<engine::Capsule>(capsule).length, 1.5);
  const engine::Shape ellipsoid = shape_of({{"ellipsoid", {1, 2, 3}}});
  EXPECT_EQ(std::get<engine::Ellipsoid>(ellipsoid).radii, Eigen::Vector3d(1, 2, 3));
  const engine::Shape cone = shape_of({{"cone", {{"radius", 0.4}, {"height", 1.2}}}});
  EXPECT_EQ(std::get<engine::Cone>(cone).radius, 0.4);
  EXPECT_EQ(std::get<engine::Cone>(cone).height, 1.2);

  const SceneDescription by_density =
      parse(shape_scene({{"sphere", {{"radius", 0.5}}}}, "density", 800));
  EXPECT_EQ(by_density.bodies[0].density, 800.0);
  EXPECT_FALSE(by_density.bodies[0].mass.has_value());
  EXPECT_EQ(scene_inputs(by_density).size(), 1u);  // the scene file alone
}

TEST(SceneShapes, MistakesNameTheFileAndTheJsonPath) {
  const auto expect_error = [](const json& shape, const std::string& message) {
    EXPECT_THAT(shape_field_error_of(shape_scene(shape)),
                AllOf(HasSubstr("scenes/shapes.json: "), HasSubstr(message)))
        << shape.dump();
  };
  expect_error({{"pyramid", {1, 2, 3}}},
               "bodies[0].shape.pyramid: unknown key; expected one of: box, sphere, cylinder, "
               "capsule, ellipsoid, cone");
  expect_error(json::object(), "bodies[0].shape: expected exactly one of {\"box\": [x, y, z]}");
  expect_error({{"box", {1, 1, 1}}, {"sphere", {{"radius", 1}}}}, "got 2 kinds");
  expect_error("box", "bodies[0].shape: expected an object, got the string \"box\"");
  expect_error({{"box", {1, 1}}}, "bodies[0].shape.box: expected the edge lengths [x, y, z]");
  expect_error({{"box", {1, -1, 1}}}, "bodies[0].shape.box[1]: expected a positive number, got -1");
  expect_error({{"ellipsoid", {1, 1, "2"}}},
               "bodies[0].shape.ellipsoid[2]: expected a number, got the string \"2\"");
  expect_error({{"sphere", 1.0}}, "bodies[0].shape.sphere: expected an object, got 1");
  expect_error({{"sphere", {{"radius", 0}}}},
               "bodies[0].shape.sphere.radius: expected a positive number, got 0");
  expect_error({{"sphere", {{"diameter", 1}}}},
               "bodies[0].shape.sphere.diameter: unknown key; expected one of: radius");
  expect_error({{"cylinder", {{"radius", 1}}}},
               "bodies[0].shape.cylinder.length: missing; expected the length along z");
  expect_error({{"capsule", {{"radius", true}, {"length", 1}}}},
               "bodies[0].shape.capsule.radius: expected a number, got true");
  expect_error({{"cone", {{"radius", 1}, {"length", 1}}}},
               "bodies[0].shape.cone.length: unknown key; expected one of: radius, height");
  expect_error({{"sphere", {{"radius", 1e150}}}},
               "bodies[0].shape: sphere: its volume (inf m^3) or moments of inertia are beyond "
               "the range of a double");
}

TEST(SceneShapes, TheBodyTakesOneOfMeshShapeOrInertiaAndItsMatter) {
  json scene = shape_scene({{"box", {1, 1, 1}}});
  scene["bodies"][0]["inertia"] = {{"principal", {1, 1, 1}}};
  EXPECT_THAT(shape_field_error_of(scene),
              HasSubstr("bodies[0]: expected exactly one of \"mesh\", \"shape\" "
                        "or \"inertia\", got 2 of them"));
  scene = shape_scene({{"box", {1, 1, 1}}});
  scene["bodies"][0]["mesh"] = "box.obj";
  EXPECT_THAT(shape_field_error_of(scene), HasSubstr("got 2 of them"));
  scene = shape_scene({{"box", {1, 1, 1}}});
  scene["bodies"][0].erase("mass");
  EXPECT_THAT(shape_field_error_of(scene),
              HasSubstr("bodies[0]: missing \"mass\" (kg) or \"density\" "
                        "(kg/m^3) for the shape"));
  scene = shape_scene({{"box", {1, 1, 1}}});
  scene["bodies"][0]["density"] = 1000;
  EXPECT_THAT(shape_field_error_of(scene),
              HasSubstr("bodies[0].density: \"mass\" and \"density\" exclude"));
  EXPECT_THAT(shape_field_error_of(shape_scene({{"box", {1, 1, 1}}}, "density", -5)),
              HasSubstr("bodies[0].density: expected a positive number, got -5"));
  scene = shape_scene({{"box", {1, 1, 1}}});
  scene["bodies"][0]["scale"] = 2;
  EXPECT_THAT(shape_field_error_of(scene),
              HasSubstr("bodies[0].scale: \"scale\" applies to a mesh only"));
}

TEST(SceneShapes, ABodyCompilesToTheClosedFormAndKeepsItsTessellation) {
  const engine::Shape cylinder = engine::Cylinder{0.5, 2.0};
  const SceneDescription scene =
      parse(shape_scene({{"cylinder", {{"radius", 0.5}, {"length", 2.0}}}}, "density", 800));
  const CompiledScene compiled = compile_scene(scene, /*keep_geometry=*/true);
  EXPECT_EQ(compiled.meshes_imported, 0u);
  const engine::MassProperties exact = engine::mass_properties(cylinder, 800.0);
  const engine::BodyModel& body = compiled.bodies[0];
  EXPECT_EQ(body.mass, exact.mass);
  const Eigen::Matrix3d p = body.principal_to_body.toRotationMatrix();
  EXPECT_TRUE((p * body.moments.asDiagonal() * p.transpose()).isApprox(exact.inertia, 1e-14));
  ASSERT_TRUE(compiled.geometry[0].has_value());
  EXPECT_EQ(compiled.geometry[0]->positions.size(),
            engine::tessellate(cylinder, kShapeSegments).positions.size());
  EXPECT_FALSE(compiled.reports[0].has_value());
  EXPECT_FALSE(compile_scene(scene).geometry[0].has_value());  // only when asked for

  // A given mass is kept exactly; a mass whose moments overflow names the body's shape.
  EXPECT_EQ(compile_scene(parse(shape_scene({{"box", {1, 2, 3}}}, "mass", 0.1))).bodies[0].mass,
            0.1);
  const std::string message = testing::input_error_of([] {
    compile_scene(parse(shape_scene({{"sphere", {{"radius", 1e100}}}}, "mass", 1e300)));
  });
  EXPECT_THAT(message, HasSubstr("scenes/shapes.json: bodies[0].shape: sphere: its moments of "
                                 "inertia for a mass of 1e+300 kg are beyond"));
}

}  // namespace
}  // namespace tumble::app
