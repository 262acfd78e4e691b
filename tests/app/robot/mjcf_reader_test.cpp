// The MJCF reader's conventions and messages (MuJoCo's own numbers: mjcf_mujoco_test.cpp).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "app/robot/robot_model.hpp"
#include "engine/mass/primitive_shapes.hpp"
#include "support/input_error.hpp"

namespace tumble::app::robot {
namespace {

using ::testing::HasSubstr;

Robot read_text(const std::string& text, const ReadOptions& options = {}) {
  return read_mjcf("/models/robot.xml", text, options);
}

std::string error_of(const std::string& text) {
  return tumble::testing::input_error_of([&] { read_text(text); }, "the model");
}

std::string model(const std::string& bodies, const std::string& head = "") {
  return "<mujoco>\n" + head + "<worldbody>\n" + bodies + "</worldbody>\n</mujoco>\n";
}

template <typename T>
const T& shape_of(const Geometry& geometry) {
  return std::get<T>(std::get<engine::Shape>(geometry.shape));
}

TEST(MjcfReader, ReadsHalfSizesAsFullShapes) {
  const Robot robot = read_text(model(R"(<body name="b">
  <geom type="box" size="0.1 0.2 0.3"/>
  <geom type="capsule" size="0.1 0.2"/>
  <geom type="cylinder" size="0.1 0.2"/>
  <geom type="ellipsoid" size="0.1 0.2 0.3"/>
  <geom size="0.1 0 0"/>
</body>
)"));
  ASSERT_EQ(robot.links.size(), 1u);
  const std::vector<Geometry>& g = robot.links[0].geometries;
  ASSERT_EQ(g.size(), 5u);
  EXPECT_EQ(shape_of<engine::Box>(g[0]).size, Eigen::Vector3d(0.2, 0.4, 0.6));
  EXPECT_EQ(shape_of<engine::Capsule>(g[1]).length, 0.4);
  EXPECT_EQ(shape_of<engine::Cylinder>(g[2]).length, 0.4);
  EXPECT_EQ(shape_of<engine::Ellipsoid>(g[3]).radii, Eigen::Vector3d(0.1, 0.2, 0.3));
  EXPECT_EQ(shape_of<engine::Sphere>(g[4]).radius, 0.1);  // MuJoCo's default type
  EXPECT_EQ(g[0].where, "body 'b' geom 0");
}

TEST(MjcfReader, AnglesAreDegreesUnlessTheCompilerSaysRadian) {
  const std::string body = "<body><geom size=\"0.1\" axisangle=\"0 0 1 90\"/></body>\n";
  const Eigen::Matrix3d quarter =
      Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Robot degrees = read_text(model(body));
  EXPECT_TRUE(degrees.links[0].geometries[0].pose.linear().isApprox(quarter, 1e-15));
  const Robot radians = read_text(model(body, "<compiler angle=\"radian\"/>\n"));
  const Eigen::Matrix3d ninety =
      Eigen::AngleAxisd(90.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_TRUE(radians.links[0].geometries[0].pose.linear().isApprox(ninety, 1e-15));
}

TEST(MjcfReader, DefaultClassesNestAndBodiesPassTheirChildclassOn) {
  const Robot robot = read_text(model(R"(<body name="a" childclass="thin">
  <geom/>
  <body name="b">
    <geom class="main" size="0.3"/>
    <geom size="0.05"/>
  </body>
</body>
)",
                                      R"(<default>
  <geom density="500"/>
  <default class="rod">
    <geom type="cylinder" size="0.1 0.5" mass="2"/>
    <default class="thin"><geom size="0.01"/></default>
  </default>
</default>
)"));
  ASSERT_EQ(robot.links.size(), 2u);
  const Geometry& rod = robot.links[0].geometries[0];
  EXPECT_EQ(shape_of<engine::Cylinder>(rod).radius, 0.01);  // "0.01" over "0.1 0.5"
  EXPECT_EQ(shape_of<engine::Cylinder>(rod).length, 1.0);
  EXPECT_EQ(rod.mass, 2.0);
  EXPECT_FALSE(rod.density);  // a mass overrides the density
  const Geometry& main = robot.links[1].geometries[0];
  EXPECT_EQ(shape_of<engine::Sphere>(main).radius, 0.3);
  EXPECT_EQ(main.density, 500.0);
  EXPECT_EQ(shape_of<engine::Cylinder>(robot.links[1].geometries[1]).radius, 0.05);
}

TEST(MjcfReader, FromtoGivesTheAxisAndTheHalfLength) {
  const Robot robot =
      read_text(model("<body><geom type=\"capsule\" size=\"0.1\" fromto=\"0 0 0 0 3 4\"/>"
                      "<geom type=\"box\" size=\"0.1\" fromto=\"1 0 0 1 0 2\"/></body>\n"));
  const Geometry& capsule = robot.links[0].geometries[0];
  EXPECT_EQ(shape_of<engine::Capsule>(capsule).length, 5.0);
  EXPECT_TRUE(capsule.pose.translation().isApprox(Eigen::Vector3d(0, 1.5, 2)));
  EXPECT_TRUE((capsule.pose.linear() * Eigen::Vector3d::UnitZ())
                  .cwiseAbs()
                  .isApprox(Eigen::Vector3d(0, 0.6, 0.8)));
  EXPECT_EQ(shape_of<engine::Box>(robot.links[0].geometries[1]).size,
            Eigen::Vector3d(0.2, 0.2, 2.0));
}

TEST(MjcfReader, NamesBodiesAndSkipsTheWorldsGeoms) {
  const Robot robot = read_text(model(
      "<geom type=\"box\" size=\"1 1 1\"/>\n<body><geom size=\"0.1\"/><body name=\"x\"/></body>\n"
      "<body><geom type=\"plane\" size=\"1 1 1\"/></body>\n"));
  ASSERT_EQ(robot.links.size(), 3u);
  EXPECT_EQ(robot.links[0].name, "body 1");  // MuJoCo's body ids
  EXPECT_EQ(robot.links[1].name, "x");
  EXPECT_EQ(robot.links[2].name, "body 3");
  EXPECT_TRUE(robot.links[2].geometries.empty());
  ASSERT_EQ(robot.links[2].notes.size(), 1u);
  EXPECT_THAT(robot.links[2].notes[0], HasSubstr("is a plane: ignored"));
  EXPECT_FALSE(robot.links[1].insert_at);  // <body name="x"/> cannot take a child
}

TEST(MjcfReader, CollisionGeomsCollideAndVisualOnesDoNot) {
  const std::string text = model(
      "<body><geom size=\"0.1\"/><geom size=\"0.2\" contype=\"0\" conaffinity=\"0\"/></body>\n"
      "<body><geom size=\"0.3\" contype=\"0\" conaffinity=\"0\"/></body>\n");
  const Robot collision = read_text(text);
  ASSERT_EQ(collision.links[0].geometries.size(), 1u);
  EXPECT_EQ(shape_of<engine::Sphere>(collision.links[0].geometries[0]).radius, 0.1);
  ASSERT_EQ(collision.links[1].geometries.size(), 1u);  // none collides: all are used
  EXPECT_THAT(collision.links[1].notes.at(0), HasSubstr("no geom collides"));
  ReadOptions visual;
  visual.from = GeometrySource::visual;
  const Robot seen = read_text(text, visual);
  EXPECT_EQ(shape_of<engine::Sphere>(seen.links[0].geometries.at(0)).radius, 0.2);
}

TEST(MjcfReader, StatedInertialAndWhereItIs) {
  const std::string text = model(
      "  <body name=\"b\">\n    <inertial pos=\"1 2 3\" mass=\"4\" diaginertia=\"1 2 3\" "
      "quat=\"0.7071067811865476 0 0 0.7071067811865476\"/>\n    <geom size=\"0.1\"/>\n"
      "  </body>\n");
  const Robot robot = read_text(text);
  const Link& link = robot.links.at(0);
  ASSERT_TRUE(link.stated && link.stated->inertia && link.inertial_bytes);
  EXPECT_EQ(link.stated->mass, 4.0);
  EXPECT_EQ(link.stated->center_of_mass, Eigen::Vector3d(1, 2, 3));
  // A quarter turn about z swaps the x and y moments.
  EXPECT_TRUE(
      link.stated->inertia->isApprox(Eigen::Vector3d(2, 1, 3).asDiagonal().toDenseMatrix(), 1e-12));
  const std::string element = text.substr(link.inertial_bytes->begin,
                                          link.inertial_bytes->end - link.inertial_bytes->begin);
  EXPECT_EQ(element.substr(0, 10), "<inertial ");
  EXPECT_EQ(element.substr(element.size() - 2), "/>");
  EXPECT_EQ(link.child_indent, "    ");
  ASSERT_TRUE(link.insert_at);
  EXPECT_EQ(text.substr(*link.insert_at - 9, 9), "name=\"b\">");
}

TEST(MjcfReader, MeshesResolveThroughMeshdirAndTakeTheirFileNames) {
  const Robot robot = read_text(
      model("<body><geom type=\"mesh\" mesh=\"arm\"/><geom type=\"mesh\" mesh=\"big\"/></body>\n",
            "<compiler meshdir=\"parts\"/>\n<asset><mesh file=\"sub/arm.stl\"/>"
            "<mesh name=\"big\" file=\"/abs/arm.obj\" scale=\"2 2 -2\"/></asset>\n"));
  const auto& arm = std::get<MeshGeometry>(robot.links[0].geometries.at(0).shape);
  EXPECT_EQ(arm.file, std::filesystem::path("/models/parts/sub/arm.stl"));
  const auto& big = std::get<MeshGeometry>(robot.links[0].geometries.at(1).shape);
  EXPECT_EQ(big.file, std::filesystem::path("/abs/arm.obj"));
  EXPECT_EQ(big.scale, Eigen::Vector3d(2, 2, -2));
}

TEST(MjcfReader, ErrorsNameTheFileTheLineAndTheAttribute) {
  EXPECT_EQ(error_of(model("<body>\n<geom type=\"box\" size=\"0.1 0.2\"/></body>\n")),
            "/models/robot.xml: line 4: body 'body 1' geom 0: size: a box takes 3 numbers (MJCF "
            "half sizes), got 2");
  EXPECT_THAT(error_of(model("<body><geom size=\"0.1 0.2 0.3 0.4\"/></body>\n")),
              HasSubstr("geom 0: size: expected 1 to 3 numbers, got 4"));
  EXPECT_THAT(error_of(model("<body><geom name=\"g\" size=\"1\" quat=\"1 0 0 0\" euler=\"0 0 "
                             "1\"/></body>\n")),
              HasSubstr("line 3: body 'body 1' geom 'g': quat and euler both give the "
                        "orientation"));
  EXPECT_THAT(error_of(model("<body><geom class=\"nope\" size=\"1\"/></body>\n")),
              HasSubstr("geom 0: unknown class 'nope'"));
  EXPECT_THAT(error_of(model("<body childclass=\"nope\"/>\n")),
              HasSubstr("body 'body 1': childclass: unknown class 'nope'"));
  EXPECT_THAT(error_of(model("<body><geom type=\"mesh\" mesh=\"gone\"/></body>\n")),
              HasSubstr("geom 0: mesh: no <mesh name=\"gone\"> in <asset>"));
  EXPECT_THAT(error_of(model("<body><geom size=\"x\"/></body>\n")),
              HasSubstr("size: 'x' is not a finite number"));
  EXPECT_THAT(error_of(model("<body><geom size=\"-1\"/></body>\n")), HasSubstr("geom 0: size: "));
  EXPECT_THAT(error_of(model("<body><geom type=\"cone\" size=\"1\"/></body>\n")),
              HasSubstr("type: unknown geom type 'cone'"));
  EXPECT_THAT(error_of(model("<body><geom type=\"sphere\" size=\"1\" fromto=\"0 0 0 0 0 "
                             "1\"/></body>\n")),
              HasSubstr("fromto: a sphere takes no fromto"));
  EXPECT_THAT(error_of(model("", "<compiler angle=\"grad\"/>\n")),
              HasSubstr("line 2: compiler: angle: expected degree or radian"));
  EXPECT_THAT(error_of(model("<body><inertial mass=\"1\" pos=\"0 0 0\" fullinertia=\"1 1 1 0 0 "
                             "0\" euler=\"0 0 1\"/></body>\n")),
              HasSubstr("inertial: fullinertia is in the body's axes"));
}

TEST(MjcfReader, RefusesWhatItWouldReadWrong) {
  EXPECT_EQ(error_of("<mujoco>\n  <include file=\"arm.xml\"/>\n</mujoco>\n"),
            "/models/robot.xml: line 2: <include file=\"arm.xml\">: included files are not read "
            "(put their contents into this file, so that its inertials can be rewritten in "
            "place)");
  EXPECT_THAT(error_of(model("<body><frame><geom size=\"1\"/></frame></body>\n")),
              HasSubstr("<frame>: not read by tumble"));
  EXPECT_THAT(error_of(model("<body><geom type=\"box\" mesh=\"m\"/></body>\n")),
              HasSubstr("fitted to it by MuJoCo"));
  EXPECT_THAT(error_of("<mujoco>\n<worldbody>\n<body>\n</worldbody>\n</mujoco>\n"),
              HasSubstr("/models/robot.xml: line 4: XML error: "));
}

}  // namespace
}  // namespace tumble::app::robot
