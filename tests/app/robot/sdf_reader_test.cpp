// The SDF reader: models, nested models, poses (link-relative only), geometry and inertials.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "app/robot/link_inertial.hpp"
#include "app/robot/robot_model.hpp"
#include "base/errors.hpp"
#include "robot_fixtures.hpp"
#include "support/run_command.hpp"

namespace tumble::app::robot {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using tumble::testing::fresh_directory;
using tumble::testing::write_file;

class SdfReader : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = fresh_directory("sdf_reader"); }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  Robot read(const std::string& body, const ReadOptions& options = {},
             const std::string& name = "robot.sdf") {
    write_file(dir_ / name, "<?xml version=\"1.0\"?>\n<sdf version=\"1.7\">\n" + body + "</sdf>\n");
    return read_robot(dir_ / name, options);
  }
  std::string error(const std::string& body) {
    try {
      read(body);
    } catch (const InputError& e) {
      return e.what();
    }
    return "(no error)";
  }
  std::filesystem::path dir_;
};

std::vector<std::string> names(const Robot& robot) {
  std::vector<std::string> out;
  for (const Link& link : robot.links) out.push_back(link.name);
  return out;
}

TEST_F(SdfReader, NestedModelsPrefixTheirLinks) {
  const Robot robot = read(R"(<model name="outer">
  <link name="a"/>
  <model name="inner"><link name="b"/><model name="deep"><link name="c"/></model></model>
</model>
)");
  EXPECT_EQ(robot.format, RobotFormat::sdf);
  EXPECT_THAT(names(robot), ElementsAre("a", "inner::b", "inner::deep::c"));
  const Robot world = read(R"(<world name="w"><model name="m1"><link name="a"/></model>
<model name="m2"><link name="a"/></model></world>
)",
                           {}, "scene.world");
  EXPECT_THAT(names(world), ElementsAre("m1::a", "m2::a"));
}

TEST_F(SdfReader, ReadsPosesGeometryAndTheStatedInertial) {
  const Robot robot = read(R"(<model name="m"><link name="a">
  <pose>5 5 5 0 0 1</pose>
  <inertial>
    <pose relative_to="a">0.1 0.2 0.3 1.5707963267948966 0 0</pose>
    <mass>2</mass>
    <inertia><ixx>1</ixx><iyy>2</iyy><izz>3</izz></inertia>
  </inertial>
  <collision name="box"><pose>1 0 0 0 0 0</pose><geometry><box><size>0.1 0.2 0.3</size></box></geometry></collision>
  <collision name="e"><geometry><ellipsoid><radii>0.1 0.2 0.3</radii></ellipsoid></geometry></collision>
  <collision name="c"><geometry><capsule><radius>0.1</radius><length>0.2</length></capsule></geometry></collision>
  <collision name="floor"><geometry><plane><normal>0 0 1</normal></plane></geometry></collision>
  <visual name="v"><geometry><sphere><radius>1</radius></sphere></geometry></visual>
</link></model>
)");
  const Link& link = robot.links.at(0);
  ASSERT_TRUE(link.stated);
  EXPECT_EQ(*link.stated->mass, 2.0);
  EXPECT_LE((link.stated->center_of_mass - Eigen::Vector3d(0.1, 0.2, 0.3)).norm(), 0.0);
  EXPECT_LE((*link.stated->inertia - Eigen::Matrix3d(Eigen::Vector3d(1, 3, 2).asDiagonal())).norm(),
            1e-15);
  ASSERT_EQ(link.geometries.size(), 3u);  // the plane is left out, with a note
  EXPECT_EQ(link.geometries[0].where, "link 'a' collision 'box'");
  EXPECT_LE((link.geometries[0].pose.translation() - Eigen::Vector3d(1, 0, 0)).norm(), 0.0);
  EXPECT_TRUE(
      std::holds_alternative<engine::Ellipsoid>(std::get<engine::Shape>(link.geometries[1].shape)));
  ASSERT_EQ(link.notes.size(), 1u);
  EXPECT_THAT(link.notes[0], HasSubstr("plane"));
  ASSERT_TRUE(link.inertial_bytes);
  EXPECT_EQ(robot.text.substr(link.inertial_bytes->begin, 10), "<inertial>");
  EXPECT_EQ(robot.text.substr(link.inertial_bytes->end - 11, 11), "</inertial>");
}

TEST_F(SdfReader, RefusesPosesRelativeToOtherFrames) {
  EXPECT_THAT(error(R"(<model name="m"><link name="a"><collision name="c">
  <pose relative_to="other">0 0 0 0 0 0</pose><geometry><sphere><radius>1</radius></sphere></geometry>
</collision></link></model>
)"),
              HasSubstr("link 'a' collision 'c': pose relative_to 'other': only poses relative to "
                        "the link itself are supported"));
  EXPECT_THAT(
      error(
          R"(<model name="m"><link name="a"><inertial><pose>0 0 0 0 0</pose></inertial></link></model>
)"),
      HasSubstr("link 'a': inertial: pose: expected 6 numbers, got '0 0 0 0 0'"));
  EXPECT_THAT(
      error(
          R"(<model name="m"><link name="a"><collision name="c"><geometry><box><size>1 -1 1</size></box></geometry></collision></link></model>
)"),
      HasSubstr("link 'a' collision 'c': box size: expected 3 positive numbers"));
}

TEST_F(SdfReader, ModelUrisResolveThroughPackagePaths) {
  std::filesystem::create_directories(dir_ / "models" / "thing");
  ReadOptions options;
  options.packages = {{"thing", dir_ / "models" / "thing"}};
  const Robot robot = read(R"(<model name="m"><link name="a"><collision name="c"><geometry>
  <mesh><uri>model://thing/meshes/part.stl</uri><scale>1 2 3</scale></mesh>
</geometry></collision></link></model>
)",
                           options);
  const auto& mesh = std::get<MeshGeometry>(robot.links[0].geometries[0].shape);
  EXPECT_EQ(mesh.file, dir_ / "models" / "thing" / "meshes" / "part.stl");
  EXPECT_EQ(mesh.scale, Eigen::Vector3d(1, 2, 3));
}

TEST_F(SdfReader, DegreesAndQuaternionPoses) {
  const Robot robot = read(R"(<model name="m"><link name="a">
  <collision name="d"><pose degrees="true">0 0 0 0 0 90</pose><geometry><sphere><radius>1</radius></sphere></geometry></collision>
  <collision name="q"><pose rotation_format="quat_xyzw">0 0 0 0 0 0.7071067811865476 0.7071067811865476</pose><geometry><sphere><radius>1</radius></sphere></geometry></collision>
</link></model>
)");
  Eigen::Matrix3d quarter;
  quarter << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  for (const Geometry& geometry : robot.links[0].geometries) {
    EXPECT_LE((geometry.pose.linear() - quarter).norm(), 1e-15) << geometry.where;
  }
}

}  // namespace
}  // namespace tumble::app::robot
