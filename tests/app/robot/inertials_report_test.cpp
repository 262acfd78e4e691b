// `tumble inertials` as library calls (app/robot/inertials_report.hpp): the per-link data
// against a box's closed-form inertia, the relative differences, a failing link, and the JSON
// against the command's --json.
#include "app/robot/inertials_report.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sstream>

#include "base/errors.hpp"
#include "robot_fixtures.hpp"
#include "support/run_command.hpp"

namespace tumble::app {
namespace {

using ::testing::HasSubstr;

/// A box link stating the mass 2 kg and a wrong inertia, and a link without geometry.
constexpr const char* kReportRobot = R"(<?xml version="1.0"?>
<robot name="report">
  <link name="box">
    <inertial>
      <mass value="2"/>
      <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>
    </inertial>
    <collision><geometry><box size="0.1 0.2 0.3"/></geometry></collision>
  </link>
  <link name="sensor">
    <inertial><mass value="0.1"/><inertia ixx="1e-5" ixy="0" ixz="0" iyy="1e-5" iyz="0" izz="1e-5"/></inertial>
  </link>
</robot>
)";

class InertialsReportTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = testing::fresh_directory("InertialsReportTest"); }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

TEST_F(InertialsReportTest, LinksCarryTheClosedFormBoxAndTheirDifferences) {
  testing::write_file(dir_ / "robot.urdf", kReportRobot);
  InertialsOptions options;
  options.robot = dir_ / "robot.urdf";
  const InertialsReport report = inertials_report(options);
  EXPECT_FALSE(report.failed());
  EXPECT_EQ(report.source, "collision");
  ASSERT_EQ(report.links.size(), 2u);
  const LinkComparison& box = report.links[0];
  EXPECT_EQ(box.name, "box");
  ASSERT_TRUE(box.result.computed);
  // The stated mass is kept: Ixx = m (b^2 + c^2) / 12 and so on.
  const double m = 2.0;
  const Eigen::Matrix3d& inertia = box.result.computed->inertia;
  EXPECT_NEAR(box.result.computed->mass, m, 1e-12);
  EXPECT_NEAR(inertia(0, 0), m * (0.04 + 0.09) / 12.0, 1e-12);
  EXPECT_NEAR(inertia(1, 1), m * (0.01 + 0.09) / 12.0, 1e-12);
  EXPECT_NEAR(inertia(2, 2), m * (0.01 + 0.04) / 12.0, 1e-12);
  // ||I_stated - I|| / ||I||, Frobenius: stated is the identity.
  ASSERT_TRUE(box.inertia);
  const double expected = (Eigen::Matrix3d::Identity() - inertia).norm() / inertia.norm();
  EXPECT_NEAR(*box.inertia, expected, 1e-12 * expected);
  ASSERT_TRUE(box.mass);
  EXPECT_NEAR(*box.mass, 0.0, 1e-15);
  EXPECT_FALSE(within_tolerance(box, 1e-3));
  // No geometry: nothing computed, nothing to compare, and --check passes it.
  EXPECT_EQ(report.links[1].name, "sensor");
  EXPECT_FALSE(report.links[1].result.computed);
  EXPECT_TRUE(within_tolerance(report.links[1], 1e-3));
}

TEST_F(InertialsReportTest, JsonIsWhatTheCommandPrints) {
  testing::write_file(dir_ / "robot.urdf", kReportRobot);
  InertialsOptions options;
  options.robot = dir_ / "robot.urdf";
  const InertialsReport report = inertials_report(options);
  const auto command = testing::run_command(testing::tumble_executable() + " inertials --json " +
                                            (dir_ / "robot.urdf").string());
  ASSERT_EQ(command.status, 0) << command.err;
  EXPECT_EQ(comparison_to_json(report.robot, report.links, report.source, 1e-3, false, report.total)
                    .dump(2) +
                "\n",
            command.out);
  std::ostringstream out, err;
  EXPECT_EQ(write_inertials(options, out, err), 0);
  EXPECT_EQ(out.str(), format_comparison(report.robot, report.links, report.source, 1e-3, false,
                                         report.total));
}

TEST_F(InertialsReportTest, MissingFileIsAnInputErrorNamingIt) {
  InertialsOptions options;
  options.robot = dir_ / "absent.urdf";
  try {
    inertials_report(options);
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_THAT(error.what(), HasSubstr("absent.urdf"));
  }
}

}  // namespace
}  // namespace tumble::app
