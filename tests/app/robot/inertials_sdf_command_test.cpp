// End-to-end tests of `tumble inertials` on SDF files: poses, nested models, the link-relative
// pose rule, and the -o / --check round trip.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "robot_fixtures.hpp"
#include "support/run_command.hpp"

namespace tumble::app {
namespace {

using ::testing::HasSubstr;
using tumble::testing::fresh_directory;
using tumble::testing::read_text;
using tumble::testing::run_command;
using tumble::testing::tumble_executable;
using tumble::testing::write_file;

constexpr const char* kModel = R"(<?xml version="1.0"?>
<sdf version="1.7">
  <!-- a two-box link and a nested model -->
  <model name="m">
    <link name="two">
      <pose>1 2 3 0 0 0.5</pose>
      <inertial>
        <pose>0.2 0 0 0 0 0</pose>
        <mass>3</mass>
        <inertia><ixx>0.005</ixx><iyy>0.07</iyy><izz>0.07</izz></inertia>
      </inertial>
      <collision name="cube"><geometry><box><size>0.1 0.1 0.1</size></box></geometry></collision>
      <collision name="long">
        <pose relative_to="two">0.3 0 0 0 0 0</pose>
        <geometry><box><size>0.2 0.1 0.1</size></box></geometry>
      </collision>
    </link>
    <model name="inner">
      <link name="ball">
        <collision name="s"><pose>0 0 0.5 0 0 0</pose><geometry><sphere><radius>0.1</radius></sphere></geometry></collision>
      </link>
    </model>
  </model>
</sdf>
)";

class InertialsSdfCommand : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = fresh_directory("inertials_sdf"); }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  tumble::testing::CommandResult inertials(const std::string& arguments) const {
    return run_command(tumble_executable() + " inertials " + arguments);
  }
  std::filesystem::path dir_;
};

TEST_F(InertialsSdfCommand, TwoBoxesMatchTheClosedFormAndNestedLinksAreNamed) {
  write_file(dir_ / "m.sdf", kModel);
  // The stated inertial is the two boxes' closed form (1 kg + 2 kg, centre x = 0.2).
  const auto result = inertials("--json --check " + path("m.sdf"));
  const auto data = nlohmann::json::parse(result.out);
  ASSERT_EQ(data["links"].size(), 2u);
  EXPECT_EQ(data["format"], "sdf");
  const auto& two = data["links"][0];
  EXPECT_TRUE(two["within_tolerance"].get<bool>()) << two.dump(2);
  EXPECT_LE(two["differences"]["inertia"].get<double>(), 1e-12);
  EXPECT_LE(two["differences"]["center_of_mass"].get<double>(), 1e-12);
  const auto& ball = data["links"][1];
  EXPECT_EQ(ball["name"], "inner::ball");
  EXPECT_NEAR(ball["computed"]["center_of_mass"][2].get<double>(), 0.5, 1e-15);
  // The ball states no inertial: the check fails on it.
  EXPECT_EQ(result.status, 4);
}

TEST_F(InertialsSdfCommand, PosesRelativeToOtherFramesAreRefused) {
  std::string text = kModel;
  text.replace(text.find("relative_to=\"two\""), 17, "relative_to=\"__model__\"");
  write_file(dir_ / "m.sdf", text);
  const auto result = inertials(path("m.sdf"));
  EXPECT_EQ(result.status, 1);
  EXPECT_THAT(result.err,
              HasSubstr(path("m.sdf") + ": link 'two' collision 'long': pose "
                                        "relative_to '__model__': only poses relative to the link "
                                        "itself are supported"));
}

TEST_F(InertialsSdfCommand, RoundTripChecksClean) {
  write_file(dir_ / "m.sdf", kModel);
  const auto write = inertials(path("m.sdf") + " -o " + path("out.sdf"));
  ASSERT_EQ(write.status, 0) << write.err;
  const std::string out = read_text(dir_ / "out.sdf");
  EXPECT_THAT(out, HasSubstr("<!-- a two-box link and a nested model -->"));
  EXPECT_THAT(out, HasSubstr("      <link name=\"ball\">\n        <!-- inertial computed by tumble "
                             "from the collision geometry; inertia method: primitive -->\n"
                             "        <inertial>\n          <pose>"));
  const auto check = inertials("--check --tolerance 1e-9 " + path("out.sdf"));
  EXPECT_EQ(check.status, 0) << check.out;
}

}  // namespace
}  // namespace tumble::app
