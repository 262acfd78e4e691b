// The URDF reader: links, stated inertials (rotated into the link's axes), geometry and its
// placement, mesh paths, and the errors that name the link and attribute.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "app/robot/link_inertial.hpp"
#include "app/robot/robot_model.hpp"
#include "app/scene/mesh_inspection.hpp"
#include "base/errors.hpp"
#include "robot_fixtures.hpp"
#include "support/run_command.hpp"

namespace tumble::app::robot {
namespace {

using ::testing::HasSubstr;
using tumble::testing::fresh_directory;
using tumble::testing::placed_box_stl;
using tumble::testing::write_file;

class UrdfReader : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = fresh_directory("urdf_reader"); }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  Robot read(const std::string& links, const ReadOptions& options = {}) {
    write_file(dir_ / "robot.urdf", "<robot name=\"r\">\n" + links + "</robot>\n");
    return read_robot(dir_ / "robot.urdf", options);
  }
  /// The InputError message reading `links` gives.
  std::string error(const std::string& links) {
    try {
      read(links);
    } catch (const InputError& e) {
      return e.what();
    }
    return "(no error)";
  }
  std::filesystem::path dir_;
};

void expect_near(const Eigen::MatrixXd& actual, const Eigen::MatrixXd& expected, double tolerance) {
  EXPECT_LE((actual - expected).norm(), tolerance * std::max(1.0, expected.norm()))
      << "actual\n"
      << actual << "\nexpected\n"
      << expected;
}

TEST_F(UrdfReader, ReadsPrimitivesWithTheirOrigins) {
  const Robot robot = read(R"(  <link name="a">
    <collision><origin xyz="1 2 3" rpy="0 0 0"/><geometry><box size="0.1 0.2 0.3"/></geometry></collision>
    <collision><geometry><cylinder radius="0.5" length="2"/></geometry></collision>
    <collision><geometry><sphere radius="0.25"/></geometry></collision>
    <collision><geometry><capsule radius="0.1" length="0.4"/></geometry></collision>
    <visual><geometry><sphere radius="9"/></geometry></visual>
  </link>
)");
  EXPECT_EQ(robot.format, RobotFormat::urdf);
  ASSERT_EQ(robot.links.size(), 1u);
  const Link& link = robot.links[0];
  EXPECT_EQ(link.name, "a");
  EXPECT_FALSE(link.stated);
  ASSERT_EQ(link.geometries.size(), 4u);
  const auto& box = std::get<engine::Box>(std::get<engine::Shape>(link.geometries[0].shape));
  expect_near(box.size, Eigen::Vector3d(0.1, 0.2, 0.3), 0);
  expect_near(link.geometries[0].pose.translation(), Eigen::Vector3d(1, 2, 3), 0);
  const auto& cylinder =
      std::get<engine::Cylinder>(std::get<engine::Shape>(link.geometries[1].shape));
  EXPECT_EQ(cylinder.radius, 0.5);
  EXPECT_EQ(cylinder.length, 2.0);
  EXPECT_EQ(std::get<engine::Sphere>(std::get<engine::Shape>(link.geometries[2].shape)).radius,
            0.25);
  EXPECT_EQ(std::get<engine::Capsule>(std::get<engine::Shape>(link.geometries[3].shape)).length,
            0.4);
  EXPECT_EQ(link.geometries[1].where, "link 'a' collision 1");
  ReadOptions visual;
  visual.from = GeometrySource::visual;
  EXPECT_EQ(read_robot(dir_ / "robot.urdf", visual).links[0].geometries.size(), 1u);
  const Robot only_visual = read(
      "<link name=\"v\"><visual><geometry><sphere radius=\"1\"/></geometry></visual></link>\n");
  EXPECT_THAT(only_visual.links[0].notes,
              ::testing::ElementsAre("has no <collision> geometry, only <visual> (--from visual)"));
}

TEST_F(UrdfReader, RotatesTheStatedInertiaIntoTheLinkAxes) {
  // Principal moments 1, 2, 3 about a frame turned 90 degrees about x: y goes to z.
  const Robot robot = read(R"(  <link name="a">
    <inertial>
      <origin xyz="0.1 0.2 0.3" rpy="1.5707963267948966 0 0"/>
      <mass value="2.5"/>
      <inertia ixx="1" ixy="0" ixz="0" iyy="2" iyz="0" izz="3"/>
    </inertial>
  </link>
)");
  const StatedInertial& stated = *robot.links[0].stated;
  EXPECT_EQ(*stated.mass, 2.5);
  expect_near(stated.center_of_mass, Eigen::Vector3d(0.1, 0.2, 0.3), 0);
  expect_near(*stated.inertia, Eigen::Vector3d(1, 3, 2).asDiagonal().toDenseMatrix(), 1e-15);
  // A product of inertia in a frame turned about z by 45 degrees: I_link = R I R^T.
  const Robot turned = read(R"(  <link name="b">
    <inertial>
      <origin rpy="0 0 0.7853981633974483"/>
      <mass value="1"/>
      <inertia ixx="1" ixy="0" ixz="0" iyy="3" iyz="0" izz="4"/>
    </inertial>
  </link>
)");
  Eigen::Matrix3d expected;
  expected << 2, -1, 0, -1, 2, 0, 0, 0, 4;
  expect_near(*turned.links[0].stated->inertia, expected, 1e-15);
}

TEST_F(UrdfReader, MissingValuesStayUnset) {
  const Robot robot = read(R"(  <link name="a">
    <inertial>
      <inertia ixx="1" ixy="0" ixz="0" iyy="2" iyz="0"/>
    </inertial>
  </link>
  <link name="b"/>
)");
  ASSERT_EQ(robot.links.size(), 2u);
  ASSERT_TRUE(robot.links[0].stated);
  EXPECT_FALSE(robot.links[0].stated->mass);
  EXPECT_FALSE(robot.links[0].stated->inertia);
  EXPECT_THAT(robot.links[0].notes.at(0), HasSubstr("izz"));
  EXPECT_FALSE(robot.links[1].stated);
  EXPECT_FALSE(robot.links[1].insert_at);  // self-closing: no place for an element
}

TEST_F(UrdfReader, FindsTheInertialElementsBytes) {
  const std::string inertial = "<inertial><mass value=\"1\"/></inertial>";
  const Robot robot = read("  <link name=\"a\">\n    " + inertial +
                           "\n  </link>\n  <link name=\"b\">\n    <visual/>\n  </link>\n");
  const Link& a = robot.links[0];
  ASSERT_TRUE(a.inertial_bytes);
  EXPECT_EQ(
      robot.text.substr(a.inertial_bytes->begin, a.inertial_bytes->end - a.inertial_bytes->begin),
      inertial);
  const Link& b = robot.links[1];
  EXPECT_FALSE(b.inertial_bytes);
  ASSERT_TRUE(b.insert_at);
  EXPECT_EQ(robot.text.substr(*b.insert_at - 15, 15), "<link name=\"b\">");
  EXPECT_EQ(b.child_indent, "    ");
}

TEST_F(UrdfReader, BadNumbersNameTheLinkAndAttribute) {
  EXPECT_THAT(
      error(
          R"(<link name="a"><collision><geometry><box size="1 2"/></geometry></collision></link>)"),
      HasSubstr("link 'a' collision 0: box size: expected 3 positive numbers, got '1 2'"));
  EXPECT_THAT(
      error(
          R"(<link name="a"><collision><geometry><sphere radius="nan"/></geometry></collision></link>)"),
      HasSubstr("link 'a' collision 0: sphere radius: expected a positive number"));
  EXPECT_THAT(
      error(
          R"(<link name="a"><collision><geometry><cylinder radius="-1" length="1"/></geometry></collision></link>)"),
      HasSubstr("cylinder radius: expected a positive number, got '-1'"));
  EXPECT_THAT(
      error(
          R"(<link name="a"><collision><origin xyz="0 0"/><geometry><sphere radius="1"/></geometry></collision></link>)"),
      HasSubstr("link 'a' collision 0: origin xyz: expected 3 numbers, got '0 0'"));
  EXPECT_THAT(error(R"(<link name="a"><inertial><mass value="heavy"/></inertial></link>)"),
              HasSubstr("link 'a': inertial: mass value: expected a number, got 'heavy'"));
  EXPECT_THAT(
      error(
          R"(<link name="a"><collision><geometry><mesh filename="m.stl" scale="1 2"/></geometry></collision></link>)"),
      HasSubstr("mesh scale: expected 1 or 3 numbers, got '1 2'"));
  EXPECT_THAT(error(R"(<link name="a"><collision><geometry/></collision></link>)"),
              HasSubstr("link 'a' collision 0: <geometry> has no box"));
  EXPECT_THAT(error("<link name=\"a\">\n<collision>\n</link>"),
              HasSubstr("robot.urdf: line 4: XML error:"));
}

TEST_F(UrdfReader, AMeshPlacedByOriginAndScaleIsTheMeshTransformedByHand) {
  // An off-centre 0.1 x 0.2 x 0.3 box, scaled by (2, 0.5, 3), turned by rpy and moved.
  const Eigen::Vector3d size(0.1, 0.2, 0.3), center(0.05, -0.02, 0.1), scale(2, 0.5, 3);
  const Eigen::Vector3d xyz(0.3, -0.1, 0.2), rpy(0.4, -0.7, 1.1);
  tumble::testing::write_stl_file(dir_ / "part.stl", placed_box_stl(size, center));
  const Robot robot = read(R"(  <link name="m">
    <collision>
      <origin xyz="0.3 -0.1 0.2" rpy="0.4 -0.7 1.1"/>
      <geometry><mesh filename="part.stl" scale="2 0.5 3"/></geometry>
    </collision>
  </link>
)");
  ComputeOptions options;
  options.density = 700;
  const LinkInertial inertial = compute_link_inertial(robot.links[0], options);
  ASSERT_TRUE(inertial.computed) << inertial.error.value_or("");
  const Eigen::Matrix3d rotation = (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
                                    Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
                                    Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
                                       .toRotationMatrix();
  Eigen::Affine3d by_hand = Eigen::Affine3d::Identity();
  by_hand.translate(xyz).rotate(rotation).scale(scale);
  tumble::testing::write_stl_file(dir_ / "moved.stl", placed_box_stl(size, center, by_hand));
  engine::MassOptions mass;
  mass.density = 700;
  const engine::MassProperties expected = inspect_file(dir_ / "moved.stl", mass).mass_properties;
  // Mesh files hold float32 corners (assimp's precision): both sides are rounded to those.
  EXPECT_NEAR(inertial.computed->mass, expected.mass, 1e-6 * expected.mass);
  expect_near(inertial.computed->center_of_mass, expected.center_of_mass, 1e-6);
  expect_near(inertial.computed->inertia, expected.inertia, 1e-6);
}

TEST_F(UrdfReader, AMirroringScaleKeepsTheVolumePositive) {
  tumble::testing::write_stl_file(dir_ / "part.stl",
                                  placed_box_stl({0.1, 0.2, 0.3}, {0.1, 0.2, 0}));
  const Robot robot = read(R"(<link name="m"><collision><geometry>
      <mesh filename="part.stl" scale="1 -1 1"/></geometry></collision></link>
)");
  ComputeOptions options;
  options.density = 1000;
  const LinkInertial inertial = compute_link_inertial(robot.links[0], options);
  ASSERT_TRUE(inertial.computed) << inertial.error.value_or("");
  EXPECT_NEAR(inertial.computed->mass, 6.0, 1e-6);  // float32 corners
  expect_near(inertial.computed->center_of_mass, Eigen::Vector3d(0.1, -0.2, 0), 1e-7);
}

TEST_F(UrdfReader, TwoBoxesCombineAboutTheirCommonCentreOfMass) {
  // 1 kg cube of 0.1 m at the origin, 2 kg 0.2 x 0.1 x 0.1 box at x = 0.3: centre x = 0.2;
  // Ixx = 3 * 0.02 / 12; Iyy = Izz = 0.02/12 + 1 * 0.2^2 + 2 * 0.05/12 + 2 * 0.1^2 = 0.07.
  const Robot robot = read(R"(<link name="two">
    <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>
    <collision><origin xyz="0.3 0 0"/><geometry><box size="0.2 0.1 0.1"/></geometry></collision>
  </link>
)");
  ComputeOptions options;
  options.density = 1000;
  const LinkInertial inertial = compute_link_inertial(robot.links[0], options);
  ASSERT_TRUE(inertial.computed);
  EXPECT_NEAR(inertial.computed->mass, 3.0, 1e-12);
  expect_near(inertial.computed->center_of_mass, Eigen::Vector3d(0.2, 0, 0), 1e-15);
  expect_near(inertial.computed->inertia,
              Eigen::Vector3d(0.005, 0.07, 0.07).asDiagonal().toDenseMatrix(), 1e-14);
}

TEST_F(UrdfReader, PackagePathsAndMissingPackages) {
  std::filesystem::create_directories(dir_ / "pkg" / "meshes");
  ReadOptions options;
  options.packages = {{"mine", dir_ / "pkg"}};
  const Robot robot = read(R"(<link name="m"><collision><geometry>
      <mesh filename="package://mine/meshes/part.stl"/></geometry></collision></link>
)",
                           options);
  EXPECT_EQ(std::get<MeshGeometry>(robot.links[0].geometries[0].shape).file,
            dir_ / "pkg" / "meshes" / "part.stl");
  EXPECT_THAT(
      error(R"(<link name="m"><collision><geometry>
      <mesh filename="package://nope/part.stl"/></geometry></collision></link>)"),
      HasSubstr(
          "link 'm' collision 0: mesh 'package://nope/part.stl': package 'nope' is not known"));
}

}  // namespace
}  // namespace tumble::app::robot
