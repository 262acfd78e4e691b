// End-to-end tests of `tumble inertials` on URDF files: the comparison, its flags, package
// paths, failing meshes, and -o / --check (the rewrite keeps every byte outside the inertial
// elements).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "app/robot/robot_model.hpp"
#include "robot_fixtures.hpp"
#include "support/run_command.hpp"

namespace tumble::app {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
using tumble::testing::fresh_directory;
using tumble::testing::placed_box_stl;
using tumble::testing::read_text;
using tumble::testing::run_command;
using tumble::testing::tumble_executable;
using tumble::testing::write_file;

/// A URDF with a comment, odd spacing, a wrong stated inertial, a mesh with an origin, and a
/// link without geometry.
constexpr const char* kRobot = R"(<?xml version="1.0"?>
<!-- kept: a comment <inertial> that is not an element -->
<robot name="test">
  <link name="box">
    <inertial>   <!-- wrong on purpose -->
      <origin xyz="0 0 0" rpy="0 0 0"/>
      <mass value="2"/>
      <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>
    </inertial>
    <collision><geometry><box size="0.1 0.2 0.3"/></geometry></collision>
  </link>
	<link name="part">
		<inertial><mass value="0.5"/><inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial>
		<collision>
			<origin xyz="0 0 0.1" rpy="0.3 0 0"/>
			<geometry><mesh filename="meshes/part.stl" scale="0.5"/></geometry>
		</collision>
	</link>
  <link name="sensor">
    <inertial><mass value="0.1"/><inertia ixx="1e-5" ixy="0" ixz="0" iyy="1e-5" iyz="0" izz="1e-5"/></inertial>
  </link>
</robot>
)";

class InertialsCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fresh_directory("inertials");
    std::filesystem::create_directories(dir_ / "meshes");
    tumble::testing::write_stl_file(dir_ / "meshes" / "part.stl",
                                    placed_box_stl({0.1, 0.1, 0.2}, {0.02, 0, 0.05}));
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  tumble::testing::CommandResult inertials(const std::string& arguments) const {
    return run_command(tumble_executable() + " inertials " + arguments);
  }
  std::filesystem::path dir_;
};

TEST_F(InertialsCommand, HelpListsEveryOptionAndTheCheckStatus) {
  const auto help = inertials("--help");
  EXPECT_EQ(help.status, 0);
  for (const char* option : {"ROBOT", "--from", "--density", "--package-path", "--frame",
                             "--allow-overlap", "--json", "-o", "--check", "--tolerance", "4 "}) {
    EXPECT_THAT(help.out, HasSubstr(option));
  }
}

TEST_F(InertialsCommand, ReportsEachLinkAndFlagsImpossibleStatedValues) {
  write_file(dir_ / "flags.urdf", R"(<robot name="r">
  <link name="zero"><inertial><mass value="0"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
    <collision><geometry><sphere radius="0.1"/></geometry></collision></link>
  <link name="triangle"><inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="3"/></inertial>
    <collision><geometry><sphere radius="0.1"/></geometry></collision></link>
  <link name="negative"><inertial><mass value="1"/><inertia ixx="1" ixy="2" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
    <collision><geometry><sphere radius="0.1"/></geometry></collision></link>
  <link name="bare"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
</robot>
)");
  const auto text = inertials(path("flags.urdf"));
  ASSERT_EQ(text.status, 0) << text.err;
  EXPECT_THAT(text.out, HasSubstr("the stated mass is zero"));
  EXPECT_THAT(text.out, HasSubstr("note: states no usable mass (none, zero or negative): filled "
                                  "with 1000 kg/m^3"));
  EXPECT_THAT(text.out, HasSubstr("break the triangle inequality"));
  EXPECT_THAT(text.out, HasSubstr("not positive definite"));
  EXPECT_THAT(text.out, HasSubstr("no <inertial> element"));
  const auto json = inertials("--json " + path("flags.urdf"));
  ASSERT_EQ(json.status, 0) << json.err;
  const auto data = nlohmann::json::parse(json.out);
  ASSERT_EQ(data["links"].size(), 4u);
  EXPECT_EQ(data["format"], "urdf");
  const auto& bare = data["links"][3];
  EXPECT_EQ(bare["name"], "bare");
  EXPECT_TRUE(bare["stated"].is_null());
  // No stated mass: water fills the sphere.
  EXPECT_NEAR(bare["computed"]["mass"].get<double>(), 1000 * 4.0 / 3 * M_PI * 0.001, 1e-9);
  EXPECT_TRUE(bare["computed"]["mass_from_density"].get<bool>());
  const auto& zero = data["links"][0];
  EXPECT_EQ(zero["problems"].size(), 1u);
  EXPECT_EQ(data["links"][1]["differences"]["mass"].get<double>(), 0.0);
}

TEST_F(InertialsCommand, DensityGivesTheMassesFromTheVolumes) {
  write_file(dir_ / "robot.urdf", kRobot);
  const auto result = inertials("--json --density 500 " + path("robot.urdf"));
  ASSERT_EQ(result.status, 0) << result.err;
  const auto data = nlohmann::json::parse(result.out);
  EXPECT_NEAR(data["links"][0]["computed"]["mass"].get<double>(), 500 * 0.006, 1e-12);
  EXPECT_NEAR(data["links"][0]["differences"]["mass"].get<double>(), 1.0 / 3.0, 1e-12);
  // The mesh, scaled by 0.5: (0.05 x 0.05 x 0.1) m^3.
  EXPECT_NEAR(data["links"][1]["computed"]["mass"].get<double>(), 500 * 0.00025, 1e-8);
  EXPECT_TRUE(data["links"][2]["computed"].is_null());
}

TEST_F(InertialsCommand, PrimitivesArePlacedByTheirOrigins) {
  // A cylinder turned by pitch pi/2 (its axis along x) and a sphere moved to (0, 0.3, 0).
  write_file(dir_ / "shapes.urdf", R"(<robot name="r">
  <link name="cylinder"><collision><origin rpy="0 1.5707963267948966 0"/>
    <geometry><cylinder radius="0.1" length="0.4"/></geometry></collision></link>
  <link name="sphere"><collision><origin xyz="0 0.3 0"/>
    <geometry><sphere radius="0.2"/></geometry></collision></link>
</robot>
)");
  const auto result = inertials("--json --density 1000 " + path("shapes.urdf"));
  ASSERT_EQ(result.status, 0) << result.err;
  const auto data = nlohmann::json::parse(result.out);
  const auto& cylinder = data["links"][0]["computed"];
  const double m = 1000 * M_PI * 0.01 * 0.4, r2 = 0.01, l2 = 0.16;
  EXPECT_NEAR(cylinder["mass"].get<double>(), m, 1e-12);
  const auto& inertia = cylinder["inertia"];
  EXPECT_NEAR(inertia[0][0].get<double>(), m * r2 / 2, 1e-14);
  EXPECT_NEAR(inertia[1][1].get<double>(), m * (3 * r2 + l2) / 12, 1e-14);
  EXPECT_NEAR(inertia[2][2].get<double>(), m * (3 * r2 + l2) / 12, 1e-14);
  EXPECT_NEAR(inertia[0][2].get<double>(), 0.0, 1e-14);
  const auto& sphere = data["links"][1]["computed"];
  EXPECT_NEAR(sphere["center_of_mass"][1].get<double>(), 0.3, 1e-15);
  const double ms = 1000 * 4.0 / 3 * M_PI * 0.008;
  EXPECT_NEAR(sphere["inertia"][0][0].get<double>(), 0.4 * ms * 0.04, 1e-13);
}

TEST_F(InertialsCommand, PackagePathsFromTheOptionAndFromRosPackagePath) {
  std::filesystem::create_directories(dir_ / "share" / "mypkg" / "meshes");
  tumble::testing::write_stl_file(dir_ / "share" / "mypkg" / "meshes" / "part.stl",
                                  placed_box_stl({0.1, 0.1, 0.1}, {0, 0, 0}));
  write_file(dir_ / "pkg.urdf", R"(<robot name="r"><link name="a"><collision><geometry>
    <mesh filename="package://mypkg/meshes/part.stl"/></geometry></collision></link></robot>
)");
  const auto missing = run_command("env -u ROS_PACKAGE_PATH " + tumble_executable() +
                                   " inertials " + path("pkg.urdf"));
  EXPECT_EQ(missing.status, 1);
  EXPECT_THAT(missing.err,
              HasSubstr("link 'a' collision 0: mesh 'package://mypkg/meshes/part.stl': "
                        "package 'mypkg' is not known"));
  // Repeatable, and ROBOT may follow it.
  const auto option = inertials("--package-path other=" + path("share") +
                                " --package-path mypkg=" + path("share/mypkg") + " " +
                                path("pkg.urdf") + " -o " + path("out.urdf"));
  EXPECT_EQ(option.status, 0) << option.err;
  EXPECT_TRUE(std::filesystem::exists(dir_ / "out.urdf"));
  const auto ros = run_command("ROS_PACKAGE_PATH=/nowhere:" + path("share") + " " +
                               tumble_executable() + " inertials " + path("pkg.urdf"));
  EXPECT_EQ(ros.status, 0) << ros.err;
  // An entry may name the package folder itself, with or without a trailing '/'.
  const auto itself = run_command("ROS_PACKAGE_PATH=" + path("share/mypkg/") + " " +
                                  tumble_executable() + " inertials " + path("pkg.urdf"));
  EXPECT_EQ(itself.status, 0) << itself.err;
  EXPECT_EQ(inertials("--package-path mypkg " + path("pkg.urdf")).status, 1);
}

TEST_F(InertialsCommand, ABrokenMeshIsAnErrorLineAndNothingIsWritten) {
  write_file(dir_ / "robot.urdf", kRobot);
  const std::string open_box = placed_box_stl({0.1, 0.1, 0.2}, {0, 0, 0});
  // Drop the last facet: the box is open.
  const std::size_t last = open_box.rfind("  facet normal");
  write_file(dir_ / "meshes" / "part.stl",
             open_box.substr(0, last) + open_box.substr(open_box.find("endsolid")));
  const auto result = inertials(path("robot.urdf") + " -o " + path("out.urdf"));
  EXPECT_EQ(result.status, 1);
  EXPECT_THAT(result.err, HasSubstr("tumble inertials: error: " + path("robot.urdf") +
                                    ": link 'part' collision 0: "));
  EXPECT_THAT(result.out, HasSubstr("link 'part': 1 geometry\n  error: "));
  EXPECT_THAT(result.out, HasSubstr("link 'box'"));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "out.urdf"));
  EXPECT_EQ(tumble::testing::directory_entries(dir_),
            (std::vector<std::string>{"meshes", "robot.urdf"}));
}

/// The bytes of `text` outside `ranges` (sorted), piece by piece.
std::vector<std::string> outside(const std::string& text,
                                 const std::vector<robot::ByteRange>& ranges) {
  std::vector<std::string> out;
  std::size_t at = 0;
  for (const robot::ByteRange& range : ranges) {
    out.push_back(text.substr(at, range.begin - at));
    at = range.end;
  }
  out.push_back(text.substr(at));
  return out;
}

/// `pieces` without the comment -o writes before each inertial ("<!-- inertial computed by
/// tumble ... -->", its line break and the indentation after it); counts them in `removed`.
std::vector<std::string> without_method_comments(std::vector<std::string> pieces,
                                                 std::size_t& removed) {
  const std::string start = "<!-- inertial computed by tumble";
  for (std::string& piece : pieces) {
    for (std::size_t at = piece.find(start); at != std::string::npos; at = piece.find(start)) {
      std::size_t end = piece.find("-->\n", at) + 4;
      while (end < piece.size() && (piece[end] == ' ' || piece[end] == '\t')) ++end;
      piece.erase(at, end - at);
      ++removed;
    }
  }
  return pieces;
}

std::vector<robot::ByteRange> inertial_ranges(const robot::Robot& robot) {
  std::vector<robot::ByteRange> out;
  for (const robot::Link& link : robot.links) {
    if (link.inertial_bytes) out.push_back(*link.inertial_bytes);
  }
  return out;
}

TEST_F(InertialsCommand, RoundTripKeepsEveryOtherByteAndChecksClean) {
  write_file(dir_ / "robot.urdf", kRobot);
  EXPECT_EQ(inertials("--check " + path("robot.urdf")).status, 4);
  for (const char* frame : {"mesh", "principal"}) {
    SCOPED_TRACE(frame);
    const auto write = inertials(std::string("--frame ") + frame + " " + path("robot.urdf") +
                                 " -o " + path("out.urdf"));
    ASSERT_EQ(write.status, 0) << write.err;
    const robot::Robot before = robot::read_robot(dir_ / "robot.urdf", {});
    const robot::Robot after = robot::read_robot(dir_ / "out.urdf", {});
    std::size_t comments = 0;
    EXPECT_EQ(outside(before.text, inertial_ranges(before)),
              without_method_comments(outside(after.text, inertial_ranges(after)), comments));
    EXPECT_EQ(comments, 2u);  // the two links with geometry name their inertia method
    EXPECT_THAT(after.text, HasSubstr("<!-- inertial computed by tumble from the collision "
                                      "geometry; inertia method: exact -->\n\t\t<inertial>"));
    // The link without geometry keeps its element byte for byte.
    const robot::ByteRange kept = *before.links[2].inertial_bytes,
                           now = *after.links[2].inertial_bytes;
    EXPECT_EQ(before.text.substr(kept.begin, kept.end - kept.begin),
              after.text.substr(now.begin, now.end - now.begin));
    const auto check = inertials("--check --tolerance 1e-9 --json " + path("out.urdf"));
    EXPECT_EQ(check.status, 0) << check.out;
    const nlohmann::json report = nlohmann::json::parse(check.out);
    for (const auto& link : report["links"]) {
      EXPECT_TRUE(link["within_tolerance"].get<bool>()) << link.dump();
      if (link["differences"]["inertia"].is_null()) continue;
      EXPECT_LE(link["differences"]["inertia"].get<double>(), 1e-12) << link.dump();
      EXPECT_LE(link["differences"]["center_of_mass"].get<double>(), 1e-12) << link.dump();
      EXPECT_EQ(link["differences"]["mass"].get<double>(), 0.0);
    }
  }
  const std::string out = read_text(dir_ / "out.urdf");
  EXPECT_THAT(out, HasSubstr("<!-- kept: a comment <inertial>"));
  // Zeros that summing triangles left at 1e-20 are written as zeros.
  EXPECT_THAT(out, Not(::testing::ContainsRegex("e-(1[3-9]|[2-9][0-9])\"")));
}

TEST_F(InertialsCommand, ACrlfFileKeepsItsLineBreaks) {
  std::string crlf;
  for (const char c : std::string(kRobot))
    crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  write_file(dir_ / "crlf.urdf", crlf);
  ASSERT_EQ(inertials(path("crlf.urdf") + " -o " + path("out.urdf")).status, 0);
  const std::string out = read_text(dir_ / "out.urdf");
  for (std::size_t at = out.find('\n'); at != std::string::npos; at = out.find('\n', at + 1)) {
    ASSERT_EQ(out[at - 1], '\r') << "a bare line feed at byte " << at;
  }
  EXPECT_EQ(inertials("--check " + path("out.urdf")).status, 0);
}

TEST_F(InertialsCommand, AMissingInertialIsInsertedAtTheLinksIndentation) {
  write_file(dir_ / "bare.urdf",
             "<robot name=\"r\">\n  <link name=\"a\">\n    <collision><geometry><box size=\"1 2 "
             "3\"/></geometry></collision>\n  </link>\n</robot>\n");
  ASSERT_EQ(inertials(path("bare.urdf") + " -o " + path("out.urdf")).status, 0);
  const std::string text = read_text(dir_ / "out.urdf");
  EXPECT_THAT(
      text,
      HasSubstr(
          "<link name=\"a\">\n    <!-- inertial computed by tumble from the collision geometry; "
          "inertia method: primitive -->\n    <inertial>\n      <origin xyz=\"0 0 0\""));
  EXPECT_THAT(text, HasSubstr("<mass value=\"6000\"/>"));
  EXPECT_EQ(inertials("--check " + path("out.urdf")).status, 0);
}

TEST_F(InertialsCommand, RefusesToOverwriteTheInputOrToWriteWhereItCannot) {
  write_file(dir_ / "robot.urdf", kRobot);
  const auto onto = inertials(path("robot.urdf") + " -o " + path("robot.urdf"));
  EXPECT_EQ(onto.status, 1);
  EXPECT_THAT(onto.err, HasSubstr("an input is never overwritten"));
  EXPECT_EQ(onto.out, "");  // refused before any work
  EXPECT_EQ(read_text(dir_ / "robot.urdf"), kRobot);
  const auto nowhere = inertials(path("robot.urdf") + " -o " + path("missing/out.urdf"));
  EXPECT_EQ(nowhere.status, 1);
  EXPECT_THAT(nowhere.err, HasSubstr("cannot write"));
  const auto folder = inertials(path("robot.urdf") + " -o " + path("meshes"));
  EXPECT_EQ(folder.status, 1);
  EXPECT_THAT(folder.err, HasSubstr("a directory"));
  EXPECT_EQ(tumble::testing::directory_entries(dir_),
            (std::vector<std::string>{"meshes", "robot.urdf"}));
  EXPECT_EQ(tumble::testing::directory_entries(dir_ / "meshes"),
            (std::vector<std::string>{"part.stl"}));
}

TEST_F(InertialsCommand, TheArmExampleShowsItsDeliberateMistakes) {
  const std::string source = TUMBLE_SOURCE_DIR;
  for (const char* file : {"arm.urdf", "arm.sdf"}) {
    SCOPED_TRACE(file);
    const std::string arguments = "--package-path tumble_assets=" + source + "/assets " + source +
                                  "/assets/robots/arm/" + file;
    const auto report = inertials(arguments);
    ASSERT_EQ(report.status, 0) << report.err;
    EXPECT_THAT(report.out, HasSubstr("break the triangle inequality"));
    EXPECT_THAT(report.out, Not(HasSubstr("error")));
    EXPECT_EQ(inertials("--check " + arguments).status, 4);
  }
}

}  // namespace
}  // namespace tumble::app
