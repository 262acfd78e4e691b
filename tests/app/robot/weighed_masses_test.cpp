// Densities and weighed masses of `tumble inertials`: SDF collision densities and
// <inertial auto="true">, --density LINK=RHO, --mass LINK=M, --total-mass M, and the whole
// robot's totals in its zero configuration, against sums and closed forms by hand.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "app/robot/inertials_report.hpp"
#include "base/errors.hpp"
#include "robot_fixtures.hpp"
#include "support/run_command.hpp"

namespace tumble::app {
namespace {

using ::testing::HasSubstr;
using tumble::testing::fresh_directory;
using tumble::testing::run_command;
using tumble::testing::tumble_executable;
using tumble::testing::write_file;

/// Link "two": a unit cube at its origin at 500 kg/m^3 (500 kg) and a 0.5 x 0.5 x 2 box
/// (0.5 m^3) 2 m along x at 2000 kg/m^3 (1000 kg): 1500 kg, centre of mass x = 2000/1500.
/// Link "auto": a unit cube at the default 1000 kg/m^3, whatever its inertial states.
constexpr const char* kWeighedSdf = R"(<?xml version="1.0"?>
<sdf version="1.11"><model name="m">
  <link name="two">
    <inertial><mass>7</mass><inertia><ixx>1</ixx><iyy>1</iyy><izz>1</izz></inertia></inertial>
    <collision name="light"><density>500</density>
      <geometry><box><size>1 1 1</size></box></geometry></collision>
    <collision name="heavy"><density>2000</density><pose>2 0 0 0 0 0</pose>
      <geometry><box><size>0.5 0.5 2</size></box></geometry></collision>
  </link>
  <link name="auto"><pose>0 0 5 0 0 0</pose>
    <inertial auto="true"><mass>99</mass></inertial>
    <collision><geometry><box><size>1 1 1</size></box></geometry></collision>
  </link>
  <joint name="j" type="revolute"><parent>two</parent><child>auto</child></joint>
</model></sdf>
)";

class WeighedMasses : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fresh_directory("weighed_masses");
    write_file(dir_ / "robot.sdf", kWeighedSdf);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  InertialsReport report(const robot::ComputeOptions& compute,
                         const std::string& name = "robot.sdf") {
    return compute_inertials(dir_ / name, {}, compute);
  }
  std::string error(const robot::ComputeOptions& compute) {
    try {
      report(compute);
    } catch (const InputError& e) {
      return e.what();
    }
    return "(no error)";
  }
  std::filesystem::path dir_;
};

TEST_F(WeighedMasses, SdfCollisionDensitiesAddUpAndAutoInertialsIgnoreStatedValues) {
  // Without --density the stated mass of 7 kg is kept (the weighed mass), so ask for the
  // densities' own with --total-mass unset: --density RHO does not override collision ones.
  robot::ComputeOptions compute;
  compute.density = 3.0;
  const InertialsReport out = report(compute);
  const auto& two = *out.links[0].result.computed;
  EXPECT_NEAR(two.mass, 1500.0, 1e-9);
  EXPECT_NEAR(two.center_of_mass.x(), 2000.0 / 1500.0, 1e-12);
  // The auto link: its stated 99 kg is not used; the global density fills its collision.
  const LinkComparison& automatic = out.links[1];
  EXPECT_FALSE(automatic.stated.has_value());
  EXPECT_NEAR(automatic.result.computed->mass, 3.0, 1e-12);
  EXPECT_TRUE(automatic.problems.empty());
  EXPECT_TRUE(within_tolerance(automatic, 1e-3));
  // Kept stated mass: the collision densities only share it out.
  const InertialsReport kept = report({});
  EXPECT_NEAR(kept.links[0].result.computed->mass, 7.0, 1e-12);
  EXPECT_NEAR(kept.links[0].result.computed->center_of_mass.x(), 2000.0 / 1500.0, 1e-12);
  EXPECT_NEAR(kept.links[1].result.computed->mass, 1000.0, 1e-9);
}

TEST_F(WeighedMasses, LinkDensityWinsOverCollisionDensities) {
  robot::ComputeOptions compute;
  compute.link_densities = {{"two", 100.0}};
  const InertialsReport out = report(compute);
  // 1.5 m^3 at 100 kg/m^3; the centre of mass now halfway weighted by volume: 2 * 0.5 / 1.5.
  EXPECT_NEAR(out.links[0].result.computed->mass, 150.0, 1e-10);
  EXPECT_NEAR(out.links[0].result.computed->center_of_mass.x(), 1.0 / 1.5, 1e-12);
  EXPECT_EQ(out.links[0].result.mass_from, "density");
}

TEST_F(WeighedMasses, MassScalesTheInertiaAndTotalMassSpreadsTheRest) {
  robot::ComputeOptions compute;
  compute.density = 1.0;
  const InertialsReport plain = report(compute);
  compute.link_masses = {{"auto", 4.0}};
  const InertialsReport weighed = report(compute);
  const auto& a = *weighed.links[1].result.computed;
  EXPECT_NEAR(a.mass, 4.0, 1e-12);
  // A unit cube of 4 kg: 4 (1 + 1) / 12 about each axis.
  EXPECT_NEAR(a.inertia(0, 0), 8.0 / 12.0, 1e-12);
  EXPECT_EQ(weighed.links[1].result.mass_from, "--mass");
  // 10 kg in all, 4 of them fixed: link "two" takes the other 6 kg, its inertia scaled.
  compute.total_mass = 10.0;
  const InertialsReport total = report(compute);
  const auto& two = *total.links[0].result.computed;
  EXPECT_NEAR(two.mass, 6.0, 1e-12);
  const auto& unscaled = *plain.links[0].result.computed;
  EXPECT_LE((two.inertia - unscaled.inertia * (6.0 / unscaled.mass)).norm(),
            1e-12 * two.inertia.norm());
  EXPECT_EQ(total.links[0].result.mass_from, "--total-mass");
  EXPECT_NEAR(total.total->properties.mass, 10.0, 1e-12);
}

TEST_F(WeighedMasses, OptionsNamingNoLinkAndImpossibleTotalsAreErrors) {
  robot::ComputeOptions compute;
  compute.link_masses = {{"nope", 2.0}};
  EXPECT_THAT(error(compute), HasSubstr("--mass 'nope=2': no link 'nope' in "));
  compute.link_masses = {{"auto", 4.0}};
  compute.total_mass = 3.0;
  EXPECT_THAT(error(compute), HasSubstr("--total-mass 3: the links' fixed masses"));
  const auto cli = run_command(tumble_executable() + " inertials --density x=abc " +
                               (dir_ / "robot.sdf").string());
  EXPECT_EQ(cli.status, 1);
  EXPECT_THAT(cli.err, HasSubstr("'x=abc': expected a positive number, got 'abc'"));
  const auto unknown = run_command(tumble_executable() + " inertials --density nope=5 " +
                                   (dir_ / "robot.sdf").string());
  EXPECT_EQ(unknown.status, 1);
  EXPECT_THAT(unknown.err, HasSubstr("--density 'nope=5': no link 'nope' in "));
}

/// Two boxes along a joint: "base", a 1 m cube at the root (1000 kg); "arm", a 2 x 1 x 1 box
/// (2000 kg) on a joint 2 m along x turned a quarter about z, so that its long side lies along
/// the model's y. Total 3000 kg at x = 4/3. About it (closed forms, box I = m (b^2 + c^2) / 12,
/// plus m d^2 on y and z for the offsets -4/3 and 2/3 along x):
/// Ixx = 1000 (2)/12 + 2000 (1 + 1)/12... with the arm's extents 1, 2, 1 along x, y, z:
/// Ixx = 2000/12 + 2000 (4 + 1)/12 = 1000; Iyy = 2000/12 + 16000/9 + 2000 (1 + 1)/12 + 8000/9
/// = 9500/3; Izz = 2000/12 + 16000/9 + 2000 (1 + 4)/12 + 8000/9 = 11000/3.
TEST_F(WeighedMasses, WholeRobotTotalsInTheZeroConfiguration) {
  write_file(dir_ / "chain.urdf", R"(<robot name="chain">
  <link name="base"><collision><geometry><box size="1 1 1"/></geometry></collision></link>
  <link name="arm"><collision><geometry><box size="2 1 1"/></geometry></collision></link>
  <joint name="j" type="revolute"><parent link="base"/><child link="arm"/>
    <origin xyz="2 0 0" rpy="0 0 1.5707963267948966"/></joint>
</robot>
)");
  robot::ComputeOptions compute;
  compute.density = 1000.0;
  const InertialsReport out = report(compute, "chain.urdf");
  ASSERT_TRUE(out.total.has_value());
  const engine::MassProperties& total = out.total->properties;
  EXPECT_NEAR(total.mass, 3000.0, 1e-9);
  EXPECT_LE((total.center_of_mass - Eigen::Vector3d(4.0 / 3.0, 0, 0)).norm(), 1e-12);
  const Eigen::Matrix3d expected =
      Eigen::Vector3d(1000.0, 9500.0 / 3.0, 11000.0 / 3.0).asDiagonal();
  EXPECT_LE((total.inertia - expected).norm(), 1e-12 * expected.norm()) << total.inertia;
  EXPECT_EQ(out.total->counted, 2u);
  // The command prints the same totals, as text and as JSON.
  const std::string file = (dir_ / "chain.urdf").string();
  const auto text = run_command(tumble_executable() + " inertials --density 1000 " + file);
  ASSERT_EQ(text.status, 0) << text.err;
  EXPECT_THAT(text.out, HasSubstr("whole robot, zero configuration (2 of 2 links"));
  EXPECT_THAT(text.out, HasSubstr("inertia xx yy zz 1000 3166.67 3666.67"));
  const auto json = run_command(tumble_executable() + " inertials --json --density 1000 " + file);
  ASSERT_EQ(json.status, 0) << json.err;
  const auto data = nlohmann::json::parse(json.out);
  EXPECT_NEAR(data["total"]["mass"].get<double>(), 3000.0, 1e-9);
  EXPECT_NEAR(data["total"]["center_of_mass"][0].get<double>(), 4.0 / 3.0, 1e-12);
}

}  // namespace
}  // namespace tumble::app

namespace tumble::app {
namespace {

TEST(InertialsUnitHint, AMeshOf111MetresSuggestsTheScaleAttributeOfItsFormat) {
  const auto dir = tumble::testing::fresh_directory("inertials_unit_hint");
  tumble::testing::write_stl_file(dir / "part.stl",
                                  tumble::testing::placed_box_stl({111, 40, 20}, {0, 0, 0}));
  write_file(dir / "r.urdf", R"(<robot name="r"><link name="a"><collision>
    <geometry><mesh filename="part.stl"/></geometry></collision></link></robot>
)");
  const InertialsReport out = compute_inertials(dir / "r.urdf", {}, {});
  EXPECT_THAT(out.links[0].notes,
              ::testing::Contains(HasSubstr("part.stl: size 111 m: is the file in millimetres? "
                                            "add scale=\"0.001 0.001 0.001\" to the <mesh>")));
  write_file(dir / "s.urdf", R"(<robot name="r"><link name="a"><collision>
    <geometry><mesh filename="part.stl" scale="0.001 0.001 0.001"/></geometry></collision></link></robot>
)");
  const InertialsReport scaled = compute_inertials(dir / "s.urdf", {}, {});
  for (const std::string& note : scaled.links[0].notes) {
    EXPECT_THAT(note, ::testing::Not(HasSubstr("is the file in")));
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace tumble::app
