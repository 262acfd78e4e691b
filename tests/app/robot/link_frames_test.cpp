// Link::frame and Link::parent from each reader: a three-link chain written by hand in URDF
// (joint origins), SDF (link poses, relative_to a link and a <frame>) and MJCF (nested bodies),
// against isometries computed by hand; and the errors of a broken tree.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "app/robot/robot_model.hpp"
#include "base/errors.hpp"
#include "robot_fixtures.hpp"
#include "support/run_command.hpp"

namespace tumble::app::robot {
namespace {

using ::testing::HasSubstr;
using tumble::testing::fresh_directory;
using tumble::testing::write_file;

class LinkFrames : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = fresh_directory("link_frames"); }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  Robot read(const std::string& name, const std::string& text) {
    write_file(dir_ / name, text);
    return read_robot(dir_ / name, {});
  }
  std::string error(const std::string& name, const std::string& text) {
    try {
      read(name, text);
    } catch (const InputError& e) {
      return e.what();
    }
    return "(no error)";
  }
  std::filesystem::path dir_;
};

const Link& link_named(const Robot& robot, const std::string& name) {
  for (const Link& link : robot.links) {
    if (link.name == name) return link;
  }
  throw std::runtime_error("no link " + name);
}

/// The chain's frames by hand: l1 is 1 m along x and a quarter turn about z; l2 is 2 m along
/// l1's y (the model's -x) and a quarter turn about l1's x. Rz(90) Rx(90) maps x to y, y to z,
/// z to x.
void expect_chain(const Robot& robot) {
  Eigen::Matrix4d l1, l2;
  l1 << 0, -1, 0, 1,  //
      1, 0, 0, 0,     //
      0, 0, 1, 0,     //
      0, 0, 0, 1;
  l2 << 0, 0, 1, -1,  //
      1, 0, 0, 0,     //
      0, 1, 0, 0,     //
      0, 0, 0, 1;
  EXPECT_LE((link_named(robot, "base").frame.matrix() - Eigen::Matrix4d::Identity()).norm(), 1e-12);
  EXPECT_LE((link_named(robot, "l1").frame.matrix() - l1).norm(), 1e-12)
      << link_named(robot, "l1").frame.matrix();
  EXPECT_LE((link_named(robot, "l2").frame.matrix() - l2).norm(), 1e-12)
      << link_named(robot, "l2").frame.matrix();
  EXPECT_EQ(link_named(robot, "base").parent, "");
  EXPECT_EQ(link_named(robot, "l1").parent, "base");
  EXPECT_EQ(link_named(robot, "l2").parent, "l1");
}

std::string urdf_chain(const std::string& extra_joint = "") {
  // Links and joints out of order: the tree does not depend on it.
  return R"(<robot name="chain">
  <link name="l2"/>
  <joint name="j2" type="revolute"><parent link="l1"/><child link="l2"/>
    <origin xyz="0 2 0" rpy="1.5707963267948966 0 0"/></joint>
  <link name="base"/>
  <link name="l1"/>
  <joint name="j1" type="continuous"><parent link="base"/><child link="l1"/>
    <origin xyz="1 0 0" rpy="0 0 1.5707963267948966"/></joint>
)" + extra_joint +
         "</robot>\n";
}

TEST_F(LinkFrames, UrdfComposesJointOriginsFromTheRoot) {
  expect_chain(read("chain.urdf", urdf_chain()));
}

TEST_F(LinkFrames, UrdfRefusesABrokenTree) {
  EXPECT_THAT(error("a.urdf", urdf_chain(R"(  <joint name="bad" type="fixed"><parent link="base"/>
    <child link="nowhere"/></joint>
)")),
              HasSubstr("a.urdf: joint 'bad': child link 'nowhere' is not a link of the file"));
  EXPECT_THAT(error("b.urdf", urdf_chain(R"(  <joint name="twice" type="fixed"><parent link="base"/>
    <child link="l2"/></joint>
)")),
              HasSubstr("b.urdf: joint 'twice': link 'l2' already has a parent (joint 'j2')"));
  EXPECT_THAT(error("c.urdf", urdf_chain(R"(  <joint name="back" type="fixed"><parent link="l2"/>
    <child link="base"/></joint>
)")),
              HasSubstr("the joints form a cycle through link"));
  EXPECT_THAT(error("d.urdf", urdf_chain(R"(  <joint name="half" type="fixed"><parent link="l2"/>
    </joint>
)")),
              HasSubstr("d.urdf: joint 'half': has no <child> element"));
}

std::string sdf_chain(const std::string& l2_pose) {
  return R"(<?xml version="1.0"?>
<sdf version="1.9"><model name="chain">
  <link name="base"/>
  <link name="l1"><pose>1 0 0 0 0 1.5707963267948966</pose></link>
  <link name="l2">)" +
         l2_pose + R"(</link>
  <frame name="f" attached_to="l1"><pose>0 2 0 0 0 0</pose></frame>
  <frame name="loop"><pose relative_to="loop2">0 0 0 0 0 0</pose></frame>
  <frame name="loop2"><pose relative_to="loop">0 0 0 0 0 0</pose></frame>
  <joint name="j1" type="revolute"><parent>base</parent><child>l1</child></joint>
  <joint name="j2" type="revolute"><parent>l1</parent><child>l2</child></joint>
  <joint name="fix" type="fixed"><parent>world</parent><child>base</child></joint>
</model></sdf>
)";
}

TEST_F(LinkFrames, SdfPlacesLinksRelativeToLinksAndFrames) {
  expect_chain(
      read("link.sdf", sdf_chain(R"(<pose relative_to="l1">0 2 0 1.5707963267948966 0 0</pose>)")));
  // The same through a <frame> attached to l1 (its pose relative to l1 by default).
  expect_chain(
      read("frame.sdf", sdf_chain(R"(<pose relative_to="f">0 0 0 1.5707963267948966 0 0</pose>)")));
  // A nested model's pose moves its links; in degrees.
  const Robot nested = read("nested.sdf", R"(<?xml version="1.0"?>
<sdf version="1.9"><model name="outer"><link name="a"/>
  <model name="inner"><pose degrees="true">0 0 3 0 0 90</pose>
    <link name="b"><pose>1 0 0 0 0 0</pose></link></model>
  <joint name="j" type="fixed"><parent>a</parent><child>inner::b</child></joint>
</model></sdf>
)");
  EXPECT_LE((link_named(nested, "inner::b").frame.translation() - Eigen::Vector3d(0, 1, 3)).norm(),
            1e-12);
  EXPECT_EQ(link_named(nested, "inner::b").parent, "a");
}

TEST_F(LinkFrames, SdfRefusesUnknownOrCyclicFrames) {
  EXPECT_THAT(error("a.sdf", sdf_chain(R"(<pose relative_to="nowhere">0 0 0 0 0 0</pose>)")),
              HasSubstr("a.sdf: model 'chain': link 'l2': placed relative to 'nowhere': no link, "
                        "frame or joint of that name in the model"));
  EXPECT_THAT(error("b.sdf", sdf_chain(R"(<pose relative_to="loop">0 0 0 0 0 0</pose>)")),
              HasSubstr("the poses refer to each other in a cycle"));
}

TEST_F(LinkFrames, MjcfComposesNestedBodies) {
  // euler in degrees (MuJoCo's default); quat w x y z of a quarter turn about x.
  expect_chain(read("chain.xml", R"(<mujoco><worldbody>
  <body name="base"><geom type="sphere" size="0.1"/>
    <body name="l1" pos="1 0 0" euler="0 0 90"><geom type="sphere" size="0.1"/>
      <body name="l2" pos="0 2 0" quat="0.7071067811865476 0.7071067811865476 0 0">
        <geom type="sphere" size="0.1"/></body></body></body>
</worldbody></mujoco>
)"));
}

}  // namespace
}  // namespace tumble::app::robot
