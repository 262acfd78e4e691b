// The MJCF reader against MuJoCo (libmujoco 2.2.2): the same files through mj_loadXML give
// each body's mass, centre of mass and principal moments, which tumble's geometry must match;
// and tumble's rewritten inertials, loaded back by MuJoCo, must read as tumble wrote them.
#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>

#include <unistd.h>

#include "app/robot/mujoco_oracle.hpp"
#include "app/robot/rewrite.hpp"
#include "app/support/text_file.hpp"
#include "engine/mass/primitive_shapes.hpp"
#include "support/stl_writer.hpp"

namespace tumble::app::robot {
namespace {

using tumble::testing::Agreement;
using tumble::testing::BodyInertial;

/// Primitives agree to rounding; convex meshes to the float32 of MuJoCo's vertices (MuJoCo
/// reads STL into floats, as tumble does, but then works on its own). The inertia tensor in
/// the body's axes agrees only to about 1e-6: MuJoCo keeps it as body_iquat and principal
/// moments, and its eigen decomposition stops there (a wrong orientation would be off by
/// tenths).
constexpr double kMjcfMujocoTolerance = 1e-9;
constexpr double kMeshTolerance = 1e-7;
constexpr double kMjcfMujocoTensorTolerance = 1e-5;

/// Bodies of every kind of primitive geom, placed by pos with euler, quat, axisangle, xyaxes,
/// zaxis and fromto; default classes (nested, by class and childclass); densities and masses
/// of their own (a class's mass over a geom's density, a size partly its class's); a plane in the
/// world, a zero-density visual geom and a geom outside the inertia groups, all of which add no
/// mass. ANGLE_UNIT, EULERSEQ and the angles are filled in.
const char* const kPrimitives = R"(<mujoco model="primitives">
  <compiler angle="ANGLE_UNIT" eulerseq="EULERSEQ" inertiagrouprange="0 2"/>
  <default>
    <geom density="800"/>
    <default class="heavy">
      <geom density="7800" type="box" size="0.05 0.02 0.01"/>
      <default class="pin">
        <geom type="capsule" size="0.015 0.04"/>
      </default>
    </default>
    <default class="weighed">
      <geom mass="0.5"/>
    </default>
    <default class="visual">
      <geom contype="0" conaffinity="0" group="1" density="0"/>
    </default>
  </default>
  <worldbody>
    <geom type="plane" size="1 1 0.1"/>
    <body name="base" pos="0 0 0.1">
      <geom type="box" size="0.1 0.08 0.02" pos="0.01 -0.02 0.03" euler="EULER_A"/>
      <geom type="cylinder" size="0.03 0.05" fromto="0 0 0 0.1 0.05 0.2" density="2700"/>
      <geom type="sphere" size="0.04" pos="0.05 0.05 -0.02" mass="0.3"/>
      <geom class="visual" type="sphere" size="0.5"/>
      <body name="arm" pos="0.2 0 0" childclass="heavy">
        <geom/>
        <geom class="pin" pos="0.1 0 0" axisangle="0 1 0 AXIS_ANGLE"/>
        <geom type="ellipsoid" size="0.03 0.02 0.01" quat="0.9 0.1 0.3 -0.2" pos="0 0.05 0"/>
        <geom type="capsule" size="0.01" fromto="0 0 0 0 0.1 0.1" mass="0.2"/>
        <geom type="sphere" size="0.2" group="3"/>
        <geom size="0.012" pos="0 -0.05 0" euler="EULER_B"/>
        <body name="hand" pos="0.2 0 0">
          <geom type="box" size="0.02 0.03 0.04" xyaxes="1 1 0 -1 1 0.5"/>
          <geom type="cylinder" size="0.02 0.01" zaxis="1 2 3" pos="0.03 0 0" class="main"/>
          <geom type="box" size="0.01" fromto="0 0 0 0.05 0 0.02"/>
          <geom type="ellipsoid" size="0.02 0.03" fromto="0 0 0 0 0 -0.1"/>
        </body>
      </body>
    </body>
    <body>
      <geom type="capsule" size="0.02 0.05" euler="EULER_B" pos="0.1 0.2 0.3"/>
      <geom type="cylinder" size="0.02 0.05" euler="EULER_A"/>
      <geom class="weighed" type="box" size="0.01 0.02 0.03" density="100" pos="0 0.1 0"/>
    </body>
  </worldbody>
</mujoco>
)";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t at; (at = text.find(from)) != std::string::npos;)
    text.replace(at, from.size(), to);
  return text;
}

/// The primitives model in degrees or radians, with an Euler sequence.
std::string primitives_model(bool degrees, const std::string& eulerseq) {
  const double unit = degrees ? 1.0 : 3.14159265358979323846 / 180.0;
  const auto angles = [&](double a, double b, double c) {
    return xml_number(a * unit) + " " + xml_number(b * unit) + " " + xml_number(c * unit);
  };
  std::string text = replaced(kPrimitives, "ANGLE_UNIT", degrees ? "degree" : "radian");
  text = replaced(text, "EULERSEQ", eulerseq);
  text = replaced(text, "EULER_A", angles(10, 20, 30));
  text = replaced(text, "EULER_B", angles(-40, 75, 5));
  return replaced(text, "AXIS_ANGLE", xml_number(90 * unit));
}

class MjcfAgainstMujoco : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = std::filesystem::temp_directory_path() /
              ("tumble_mjcf_" + std::to_string(::getpid()) + "_" +
               ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(folder_ / "meshes");
  }
  void TearDown() override { std::filesystem::remove_all(folder_); }

  Robot read(const std::filesystem::path& file) {
    return read_mjcf(file, read_text_file(file, "robot file"), {});
  }

  /// Compares every body of `file` that states no inertial, as MuJoCo and tumble see it.
  Agreement compare(const std::filesystem::path& file, double length = 0.1) {
    const Robot robot = read(file);
    const std::vector<BodyInertial> mujoco = tumble::testing::mujoco_bodies(file);
    const auto ours = tumble::testing::tumble_inertials(robot);
    EXPECT_EQ(mujoco.size(), robot.links.size());
    Agreement agreement;
    for (std::size_t i = 0; i < std::min(mujoco.size(), robot.links.size()); ++i) {
      SCOPED_TRACE(robot.links[i].name);
      if (!mujoco[i].name.empty()) {
        EXPECT_EQ(mujoco[i].name, robot.links[i].name);
      }
      EXPECT_FALSE(robot.links[i].stated);
      EXPECT_TRUE(ours[i]);
      if (ours[i]) agreement.add(mujoco[i], *ours[i], length);
    }
    return agreement;
  }

  /// Writes `robot` with tumble's inertials (`frame`), loads that with MuJoCo and compares.
  Agreement round_trip(const std::filesystem::path& file, InertialFrame frame,
                       double length = 0.1) {
    const Robot robot = read(file);
    const auto ours = tumble::testing::tumble_inertials(robot);
    const std::filesystem::path written = file.parent_path() / "written.xml";
    tumble::testing::write_text(written, rewritten_text(robot, ours, frame));
    const Robot again = read(written);
    const std::vector<BodyInertial> mujoco = tumble::testing::mujoco_bodies(written);
    EXPECT_EQ(mujoco.size(), ours.size());
    Agreement agreement;
    for (std::size_t i = 0; i < std::min(mujoco.size(), ours.size()); ++i) {
      EXPECT_TRUE(again.links[i].stated);  // the element tumble wrote reads back
      if (ours[i]) agreement.add(mujoco[i], *ours[i], length);
    }
    return agreement;
  }

  static void expect_close(const Agreement& agreement, const std::string& what,
                           double tolerance = kMjcfMujocoTolerance) {
    tumble::testing::expect_agreement(agreement, what, tolerance, kMjcfMujocoTensorTolerance);
  }

  std::filesystem::path folder_;
};

TEST_F(MjcfAgainstMujoco, PrimitiveGeomsGiveMujocosInertials) {
  for (const bool degrees : {true, false}) {
    for (const char* eulerseq : {"xyz", "ZYX", "zxZ", "XyX"}) {
      const std::string what = std::string(degrees ? "degree" : "radian") + " eulerseq " + eulerseq;
      const std::filesystem::path file = folder_ / "primitives.xml";
      tumble::testing::write_text(file, primitives_model(degrees, eulerseq));
      expect_close(compare(file), "primitives, " + what);
    }
  }
}

TEST_F(MjcfAgainstMujoco, RewrittenInertialsReadBackInMujoco) {
  const std::filesystem::path file = folder_ / "primitives.xml";
  tumble::testing::write_text(file, primitives_model(true, "xyz"));
  expect_close(round_trip(file, InertialFrame::mesh), "primitives rewritten (fullinertia)");
  expect_close(round_trip(file, InertialFrame::principal),
               "primitives rewritten (quat + diaginertia)");
}

/// A convex mesh away from the origin and turned: a 24-sided prism, moved and rotated.
void write_convex_mesh(const std::filesystem::path& file) {
  engine::TriangleMesh mesh = engine::tessellate(engine::Cylinder{0.05, 0.12}, 24);
  const Eigen::Matrix3d turn =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, -0.5).normalized()).toRotationMatrix();
  for (Eigen::Vector3d& p : mesh.positions) p = turn * p + Eigen::Vector3d(0.03, -0.02, 0.05);
  tumble::testing::write_binary_stl(file, mesh);
}

/// MuJoCo 2.2.2's default mesh inertia (exactmeshinertia="false") is off by 4.7 % in mass for
/// this convex prism; its exact one is the oracle.
const char* const kMeshModel = R"(<mujoco model="mesh">
  <compiler meshdir="meshes" exactmeshinertia="true"/>
  <asset>
    <mesh file="prism.stl"/>
    <mesh name="stretched" file="prism.stl" scale="1.5 0.5 2"/>
  </asset>
  <worldbody>
    <body name="plain">
      <geom type="mesh" mesh="prism" density="2000"/>
    </body>
    <body name="placed">
      <geom type="mesh" mesh="stretched" pos="0.1 0 0.02" euler="30 0 45"/>
      <geom type="box" size="0.02 0.03 0.01" pos="-0.05 0 0" mass="0.4"/>
    </body>
    <body name="weighed">
      <geom type="mesh" mesh="prism" mass="0.7" quat="0.5 0.5 -0.5 0.5" pos="0 0 -0.1"/>
      <geom type="sphere" size="0.03" pos="0.05 0 0"/>
    </body>
  </worldbody>
</mujoco>
)";

TEST_F(MjcfAgainstMujoco, ConvexMeshGeomsGiveMujocosInertials) {
  write_convex_mesh(folder_ / "meshes" / "prism.stl");
  const std::filesystem::path file = folder_ / "mesh.xml";
  tumble::testing::write_text(file, kMeshModel);
  expect_close(compare(file), "convex mesh geoms", kMeshTolerance);
  expect_close(round_trip(file, InertialFrame::mesh), "convex mesh geoms rewritten (fullinertia)");
  expect_close(round_trip(file, InertialFrame::principal),
               "convex mesh geoms rewritten (quat + diaginertia)");
}

TEST_F(MjcfAgainstMujoco, StatedInertialsReadAsMujocoReadsThem) {
  const std::filesystem::path file = folder_ / "stated.xml";
  tumble::testing::write_text(file, R"(<mujoco>
  <compiler angle="radian"/>
  <worldbody>
    <body name="diagonal">
      <inertial pos="0.1 -0.2 0.3" mass="2.5" diaginertia="0.01 0.02 0.025" euler="0.3 -0.2 1.1"/>
      <geom type="sphere" size="0.1"/>
    </body>
    <body name="full">
      <inertial pos="0 0 0.05" mass="1.5" fullinertia="0.03 0.04 0.05 0.001 -0.002 0.003"/>
    </body>
    <body name="turned">
      <inertial pos="0 0 0" mass="1" diaginertia="0.1 0.2 0.25" axisangle="1 1 0 0.5"/>
    </body>
  </worldbody>
</mujoco>
)");
  const Robot robot = read(file);
  const std::vector<BodyInertial> mujoco = tumble::testing::mujoco_bodies(file);
  ASSERT_EQ(robot.links.size(), mujoco.size());
  Agreement agreement;
  for (std::size_t i = 0; i < mujoco.size(); ++i) {
    const std::optional<StatedInertial>& stated = robot.links[i].stated;
    ASSERT_TRUE(stated && stated->mass && stated->inertia) << robot.links[i].name;
    agreement.add(mujoco[i], {*stated->mass, stated->center_of_mass, *stated->inertia}, 0.1);
  }
  expect_close(agreement, "stated inertials");
}

TEST_F(MjcfAgainstMujoco, ShippedArmGivesMujocosInertials) {
  // A copy, so that the rewritten file can sit beside it and find the mesh the same way.
  const std::filesystem::path assets = std::filesystem::path(TUMBLE_SOURCE_DIR) / "assets";
  const std::filesystem::path file = folder_ / "robots" / "arm" / "arm.xml";
  std::filesystem::create_directories(file.parent_path());
  std::filesystem::copy_file(assets / "robots" / "arm" / "arm.xml", file);
  std::filesystem::copy_file(assets / "meshes" / "rugby_ball.obj",
                             folder_ / "meshes" / "rugby_ball.obj");
  expect_close(compare(file, 0.3), "assets/robots/arm/arm.xml", kMeshTolerance);
  expect_close(round_trip(file, InertialFrame::principal, 0.3),
               "assets/robots/arm/arm.xml rewritten (quat + diaginertia)");
}

/// MuJoCo's own sample models (libmujoco-samples) whose geoms all collide and that include no
/// other file: every body's inertial from its geoms, as MuJoCo computes it.
TEST_F(MjcfAgainstMujoco, MujocosSampleModelsGiveMujocosInertials) {
  const std::filesystem::path samples = "/usr/share/mujoco/model";
  if (!std::filesystem::is_directory(samples)) GTEST_SKIP() << "libmujoco-samples is not installed";
  for (const char* name : {"humanoid/humanoid.xml", "humanoid/22_humanoids.xml",
                           "slider_crank/slider_crank.xml", "tendon_arm/arm26.xml"}) {
    const std::filesystem::path file = samples / name;
    if (!std::filesystem::exists(file)) continue;
    expect_close(compare(file, 1.0), std::string("MuJoCo sample ") + name);
  }
}

}  // namespace
}  // namespace tumble::app::robot
