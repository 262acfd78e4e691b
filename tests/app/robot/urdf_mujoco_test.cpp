// The URDF reader and the rewrite against MuJoCo 2.2.2, which reads URDF too: tumble's
// inertials for a robot of primitives and a mesh, written into the file with `-o`'s rewrite in
// either frame, must be what MuJoCo's compiler makes of that file, body by body.
#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <iostream>

#include "app/robot/mujoco_oracle.hpp"
#include "app/robot/rewrite.hpp"
#include "app/support/text_file.hpp"
#include "engine/mass/primitive_shapes.hpp"
#include "support/stl_writer.hpp"

namespace tumble::app::robot {
namespace {

using tumble::testing::Agreement;
using tumble::testing::BodyInertial;

// MuJoCo keeps an inertia as principal moments and a rotation from its own eigen
// decomposition (good to ~1e-7, mjcf_mujoco_test.cpp measures it): the tensor it implies is
// compared more loosely than mass, centre of mass and moments.
constexpr double kUrdfMujocoTolerance = 1e-9;
constexpr double kUrdfMujocoTensorTolerance = 1e-5;

// Three links joined by revolute joints (MuJoCo fuses links joined by fixed ones, and the root
// link, empty here, becomes its world body): primitives
// placed by origins with rpy, two geometries in one link, a mesh turned and scaled, stated
// inertials that are all wrong.
const char* const kRobot = R"(<?xml version="1.0"?>
<robot name="oracle">
  <!-- the stated inertials are placeholders; tumble's replace them -->
  <link name="root"/>
  <joint name="j0" type="revolute">
    <parent link="root"/><child link="base"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
  <link name="base">
    <inertial><mass value="4"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
    <collision>
      <origin xyz="0.01 -0.02 0.05" rpy="0.3 -0.2 0.9"/>
      <geometry><box size="0.2 0.12 0.1"/></geometry>
    </collision>
    <collision>
      <origin xyz="0 0 0.15" rpy="1.5707963267948966 0 0"/>
      <geometry><cylinder radius="0.04" length="0.2"/></geometry>
    </collision>
  </link>
  <joint name="j1" type="revolute">
    <parent link="base"/><child link="arm"/>
    <origin xyz="0 0 0.3" rpy="0 0.4 0"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
  <link name="arm">
    <inertial>
      <origin xyz="0 0 0.1" rpy="0.1 0.2 0.3"/>
      <mass value="1.5"/>
      <inertia ixx="0.01" ixy="0.001" ixz="0" iyy="0.02" iyz="0" izz="0.015"/>
    </inertial>
    <collision>
      <origin xyz="0 0.01 0.12" rpy="0 0 0"/>
      <geometry><cylinder radius="0.025" length="0.24"/></geometry>
    </collision>
    <collision>
      <origin xyz="0.02 0 0.26" rpy="0 0 0"/>
      <geometry><sphere radius="0.035"/></geometry>
    </collision>
  </link>
  <joint name="j2" type="revolute">
    <parent link="arm"/><child link="hand"/>
    <origin xyz="0 0 0.3"/><axis xyz="1 0 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
  <link name="hand">
    <inertial><mass value="0.4"/><inertia ixx="1e-3" ixy="0" ixz="0" iyy="1e-3" iyz="0" izz="1e-3"/></inertial>
    <collision>
      <origin xyz="0.03 -0.01 0.04" rpy="0.5 0.25 -1.0"/>
      <geometry><mesh filename="prism.stl" scale="1 2 0.5"/></geometry>
    </collision>
  </link>
</robot>
)";

class UrdfAgainstMujoco : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = std::filesystem::temp_directory_path() /
              ("tumble_urdf_mujoco_" + std::to_string(::getpid()) + "_" +
               ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(folder_);
    // A convex prism off its centre, so the mesh's own centre of mass and axes matter.
    engine::TriangleMesh mesh = engine::tessellate(engine::Cylinder{0.03, 0.08}, 12);
    for (Eigen::Vector3d& p : mesh.positions) p += Eigen::Vector3d(0.01, 0.0, -0.02);
    tumble::testing::write_binary_stl(folder_ / "prism.stl", mesh);
    tumble::testing::write_text(folder_ / "robot.urdf", kRobot);
  }
  void TearDown() override { std::filesystem::remove_all(folder_); }

  /// MuJoCo's bodies in tumble's order of links: every link but the empty root.
  static std::vector<BodyInertial> mujoco_links(const std::filesystem::path& file,
                                                const Robot& robot) {
    std::vector<BodyInertial> bodies = tumble::testing::mujoco_bodies(file);
    EXPECT_EQ(bodies.size() + 1, robot.links.size());
    EXPECT_EQ(robot.links.front().name, "root");
    bodies.insert(bodies.begin(), BodyInertial{});
    return bodies;
  }

  /// Writes the robot with tumble's inertials in `frame`, loads that with MuJoCo and compares.
  Agreement round_trip(InertialFrame frame) {
    const std::filesystem::path file = folder_ / "robot.urdf";
    const Robot robot = read_urdf(file, read_text_file(file, "robot file"), {});
    const auto ours = tumble::testing::tumble_inertials(robot);
    const std::filesystem::path written = folder_ / "written.urdf";
    tumble::testing::write_text(written, rewritten_text(robot, ours, frame));
    const std::vector<BodyInertial> mujoco = mujoco_links(written, robot);
    Agreement agreement;
    for (std::size_t i = 1; i < std::min(mujoco.size(), robot.links.size()); ++i) {
      SCOPED_TRACE(robot.links[i].name);
      EXPECT_EQ(mujoco[i].name, robot.links[i].name);
      EXPECT_TRUE(ours[i]);
      // The stated masses are kept; the shape decides the rest.
      EXPECT_DOUBLE_EQ(mujoco[i].mass, *robot.links[i].stated->mass);
      if (ours[i]) agreement.add(mujoco[i], *ours[i], 0.1);
    }
    return agreement;
  }

  static void expect_close(const Agreement& agreement, const std::string& what) {
    tumble::testing::expect_agreement(agreement, what, kUrdfMujocoTolerance,
                                      kUrdfMujocoTensorTolerance);
  }

  std::filesystem::path folder_;
};

TEST_F(UrdfAgainstMujoco, RewrittenInertialsInTheMeshFrameReadBackInMujoco) {
  expect_close(round_trip(InertialFrame::mesh), "URDF rewritten, link axes");
}

TEST_F(UrdfAgainstMujoco, RewrittenInertialsInThePrincipalFrameReadBackInMujoco) {
  expect_close(round_trip(InertialFrame::principal), "URDF rewritten, principal axes (rpy)");
}

// The stated placeholders themselves are read as MuJoCo reads them (origin rpy included).
TEST_F(UrdfAgainstMujoco, StatedInertialsReadAsMujocoReadsThem) {
  const std::filesystem::path file = folder_ / "robot.urdf";
  const Robot robot = read_urdf(file, read_text_file(file, "robot file"), {});
  const std::vector<BodyInertial> mujoco = mujoco_links(file, robot);
  ASSERT_EQ(mujoco.size(), robot.links.size());
  Agreement agreement;
  for (std::size_t i = 1; i < robot.links.size(); ++i) {
    EXPECT_EQ(mujoco[i].name, robot.links[i].name);
    const StatedInertial& stated = *robot.links[i].stated;
    engine::MassProperties as_stated;
    as_stated.mass = *stated.mass;
    as_stated.center_of_mass = stated.center_of_mass;
    as_stated.inertia = *stated.inertia;
    agreement.add(mujoco[i], as_stated, 0.1);
  }
  expect_close(agreement, "URDF stated inertials");
}

}  // namespace
}  // namespace tumble::app::robot
