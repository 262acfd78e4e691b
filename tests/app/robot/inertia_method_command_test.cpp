// The inertia methods end to end: `tumble inspect --inertia` and `tumble inertials --inertia`
// name the method in every output (text, JSON, JSONL, the table, the comments of a rewritten
// file), and MJCF's own mesh inertia attributes are followed. Oracles: the closed forms of a
// box and of an L-prism's hull (3.5 of the L's 3 m^3 at unit height), and a box's surface.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <sstream>

#include "engine/geometry/primitive_meshes.hpp"
#include "robot_fixtures.hpp"
#include "support/l_prism.hpp"
#include "support/run_command.hpp"
#include "support/stl_writer.hpp"

namespace tumble::app {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::Not;
using tumble::testing::fresh_directory;
using tumble::testing::read_text;
using tumble::testing::run_command;
using tumble::testing::tumble_executable;
using tumble::testing::write_file;

/// The cube of side `side` at the origin without its two triangles at z = +side/2.
engine::TriangleMesh open_cube(double side) {
  engine::TriangleMesh mesh = engine::box_mesh(Eigen::Vector3d::Constant(side));
  std::erase_if(mesh.triangles, [&](const std::array<std::uint32_t, 3>& t) {
    return std::all_of(t.begin(), t.end(),
                       [&](std::uint32_t v) { return mesh.positions[v].z() > 0.25 * side; });
  });
  return mesh;
}

/// inspect --json prints an object for one file, an array for several.
nlohmann::json first_report(const std::string& out) {
  const nlohmann::json parsed = nlohmann::json::parse(out);
  return parsed.is_array() ? parsed[0] : parsed;
}

class InertiaMethodCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fresh_directory("inertia_method");
    tumble::testing::write_binary_stl(dir_ / "open.stl", open_cube(0.5));
    tumble::testing::write_binary_stl(dir_ / "cube.stl",
                                      engine::box_mesh(Eigen::Vector3d::Constant(0.5)));
    tumble::testing::write_binary_stl(dir_ / "l.stl", tumble::testing::l_prism());
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  tumble::testing::CommandResult tumble(const std::string& arguments) const {
    return run_command(tumble_executable() + " " + arguments);
  }
  std::filesystem::path dir_;
};

TEST_F(InertiaMethodCommand, InspectNamesTheMethodInTextJsonAndJsonl) {
  const auto refused = tumble("inspect " + path("open.stl"));
  EXPECT_NE(refused.status, 0);
  EXPECT_THAT(refused.err, HasSubstr("the surface is open (4 boundary edges)"));

  const auto text = tumble("inspect --inertia convex --density 2 " + path("open.stl"));
  ASSERT_EQ(text.status, 0) << text.err;
  EXPECT_THAT(text.out, HasSubstr("inertia           convex (the convex hull's solid)"));
  EXPECT_THAT(text.out, HasSubstr("mass              0.25 kg"));  // 2 kg/m^3 x 0.125 m^3

  const auto json = tumble("inspect --json --inertia convex --density 2 " + path("open.stl"));
  ASSERT_EQ(json.status, 0) << json.err;
  const auto report = first_report(json.out);
  EXPECT_EQ(report["method"], "convex");
  EXPECT_NEAR(report["hull_volume"].get<double>(), 0.125, 1e-15);
  EXPECT_TRUE(report["enclosed_volume"].is_null());
  EXPECT_NEAR(report["mass"].get<double>(), 0.25, 1e-15);

  const auto lines =
      tumble("inspect --jsonl --inertia auto " + path("open.stl") + " " + path("cube.stl"));
  ASSERT_EQ(lines.status, 0) << lines.err;
  std::istringstream stream(lines.out);
  std::vector<nlohmann::json> records;
  for (std::string line; std::getline(stream, line);)
    records.push_back(nlohmann::json::parse(line));
  ASSERT_GE(records.size(), 2u);
  const auto find = [&](const std::string& name) {
    for (const auto& r : records) {
      if (r.contains("file") && r["file"].get<std::string>().ends_with(name)) return r;
    }
    return nlohmann::json();
  };
  EXPECT_EQ(find("open.stl")["method"], "convex");
  EXPECT_THAT(find("open.stl")["exact_refused"].get<std::string>(), HasSubstr("4 boundary edges"));
  EXPECT_THAT(find("open.stl")["warnings"][0].get<std::string>(),
              HasSubstr("exact inertia refused (the surface is open"));
  EXPECT_EQ(find("cube.stl")["method"], "exact");
}

TEST_F(InertiaMethodCommand, InspectConvexStatesBothVolumesAndWarns) {
  const auto text = tumble("inspect --inertia convex " + path("l.stl"));
  ASSERT_EQ(text.status, 0) << text.err;
  EXPECT_THAT(text.out,
              AllOf(HasSubstr("enclosed volume   3 m^3"), HasSubstr("volume            3.5 m^3"),
                    HasSubstr("16.6667% more than the volume the mesh encloses")));
}

TEST_F(InertiaMethodCommand, InspectLegacyNamesMuJocosApproximationAndExactsVolume) {
  const auto text = tumble("inspect --inertia legacy " + path("l.stl"));
  ASSERT_EQ(text.status, 0) << text.err;
  EXPECT_THAT(text.out, AllOf(HasSubstr("inertia           legacy (MuJoCo's approximation)"),
                              HasSubstr("enclosed volume   3 m^3"),
                              HasSubstr("volume            3.41565028 m^3"),
                              HasSubstr("MuJoCo's legacy approximation: closure and winding not "
                                        "required (0 boundary edges)"),
                              HasSubstr("% more than the solid the mesh encloses (3 m^3")));
  const auto json = tumble("inspect --json --inertia legacy " + path("cube.stl"));
  ASSERT_EQ(json.status, 0) << json.err;
  const auto report = first_report(json.out);
  EXPECT_EQ(report["method"], "legacy");
  EXPECT_NEAR(report["enclosed_volume"].get<double>(), 0.125, 1e-15);
  EXPECT_NEAR(report["mass"].get<double>(), 1000 * 0.125, 1e-9);  // convex: legacy is exact
}

TEST_F(InertiaMethodCommand, InspectShellByMassAndByThickness) {
  const auto mass = tumble("inspect --json --inertia shell --mass 3 " + path("cube.stl"));
  ASSERT_EQ(mass.status, 0) << mass.err;
  const auto report = first_report(mass.out);
  EXPECT_EQ(report["method"], "shell");
  EXPECT_NEAR(report["areal_density"].get<double>(), 3.0 / (6 * 0.25), 1e-12);
  // A box's surface: I = m s^2 5/18 about the centre.
  EXPECT_NEAR(report["principal_moments"][0].get<double>(), 3.0 * 0.25 * 5.0 / 18.0, 1e-12);

  const auto thickness = tumble("inspect --json --shell 0.01 " + path("open.stl"));
  ASSERT_EQ(thickness.status, 0) << thickness.err;
  EXPECT_EQ(first_report(thickness.out)["method"], "shell");

  const auto neither = tumble("inspect --inertia shell " + path("cube.stl"));
  EXPECT_NE(neither.status, 0);
  EXPECT_THAT(neither.err, HasSubstr("the shell inertia method needs a thickness (--shell T) or "
                                     "a total mass (--mass M)"));
}

TEST_F(InertiaMethodCommand, InertialsNamesTheMethodPerLinkAndInTheRewrittenFile) {
  write_file(dir_ / "robot.urdf", R"(<robot name="r">
  <link name="bin">
    <inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
    <collision><geometry><mesh filename="open.stl"/></geometry></collision>
  </link>
  <link name="ball"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
</robot>
)");
  const auto refused = tumble("inertials " + path("robot.urdf"));
  EXPECT_NE(refused.status, 0);
  EXPECT_THAT(refused.err, HasSubstr("the surface is open"));

  const auto text = tumble("inertials --inertia auto " + path("robot.urdf"));
  ASSERT_EQ(text.status, 0) << text.err;
  EXPECT_THAT(text.out, HasSubstr("inertia method: convex"));
  EXPECT_THAT(text.out, HasSubstr("inertia method: primitive"));
  EXPECT_THAT(text.out, HasSubstr("exact inertia refused (the surface is open"));

  const auto json = tumble("inertials --json --inertia auto " + path("robot.urdf"));
  ASSERT_EQ(json.status, 0) << json.err;
  const auto links = nlohmann::json::parse(json.out)["links"];
  EXPECT_EQ(links[0]["computed"]["method"], "convex");
  // The stated mass kept: the full box of side 0.5, I = m s^2 / 6.
  EXPECT_NEAR(links[0]["computed"]["inertia"][0][0].get<double>(), 0.25 / 6.0, 1e-12);
  EXPECT_EQ(links[1]["computed"]["method"], "primitive");

  const auto written =
      tumble("inertials --inertia auto -o " + path("out.urdf") + " " + path("robot.urdf"));
  ASSERT_EQ(written.status, 0) << written.err;
  EXPECT_THAT(read_text(dir_ / "out.urdf"),
              AllOf(HasSubstr("<!-- inertial computed by tumble from the collision geometry; "
                              "inertia method: convex -->\n    <inertial>"),
                    HasSubstr("inertia method: primitive -->")));
}

TEST_F(InertiaMethodCommand, MjcfMeshInertiaAttributesAreFollowed) {
  write_file(dir_ / "model.xml", R"(<mujoco>
  <compiler inertiafromgeom="true"/>
  <asset>
    <mesh name="hull" file="l.stl" inertia="convex"/>
    <mesh name="whole" file="l.stl" inertia="exact"/>
    <mesh name="old" file="l.stl" inertia="legacy"/>
    <mesh name="skin" file="cube.stl"/>
  </asset>
  <worldbody>
    <body name="a"><inertial pos="0 0 0" mass="1" diaginertia="1 1 1"/>
      <geom type="mesh" mesh="hull" density="2"/></body>
    <body name="b"><geom type="mesh" mesh="whole" density="2"/></body>
    <body name="c"><geom type="mesh" mesh="old" density="2"/></body>
    <body name="d"><geom type="mesh" mesh="skin" density="2" shellinertia="true"/></body>
  </worldbody>
</mujoco>
)");
  const auto json = tumble("inertials --json " + path("model.xml"));
  ASSERT_EQ(json.status, 0) << json.err;
  const auto links = nlohmann::json::parse(json.out)["links"];
  EXPECT_EQ(links[0]["computed"]["method"], "convex");
  EXPECT_THAT(links[0]["notes"].dump(), HasSubstr("inertiafromgeom"));
  EXPECT_EQ(links[1]["computed"]["method"], "exact");
  EXPECT_NEAR(links[1]["computed"]["mass"].get<double>(), 2 * 3.0, 1e-12);
  // legacy: MuJoCo's approximation (tests/app/robot/mjcf_legacy_mujoco_test.cpp checks it
  // against MuJoCo), 13.9% more than the L's 3 m^3.
  EXPECT_EQ(links[2]["computed"]["method"], "legacy");
  EXPECT_NEAR(links[2]["computed"]["mass"].get<double>(), 2 * 3.41565, 2 * 1e-5);
  EXPECT_THAT(links[2]["notes"].dump(),
              AllOf(HasSubstr("inertia method legacy as the file asks"), HasSubstr("13.8")));
  EXPECT_EQ(links[3]["computed"]["method"], "shell");
  // shellinertia: the density is per area, as MuJoCo reads it: 2 kg/m^2 x 6 x 0.25 m^2.
  EXPECT_NEAR(links[3]["computed"]["mass"].get<double>(), 2 * 6 * 0.25, 1e-12);

  const auto hull_mass = tumble("inertials --json --density 2 " + path("model.xml"));
  ASSERT_EQ(hull_mass.status, 0) << hull_mass.err;
  EXPECT_NEAR(nlohmann::json::parse(hull_mass.out)["links"][0]["computed"]["mass"].get<double>(),
              2 * 3.5, 1e-12);

  const auto bad = tumble("inertials " + path("model.xml") + " --inertia nonsense");
  EXPECT_NE(bad.status, 0);
  EXPECT_THAT(bad.err, HasSubstr("--inertia"));
  EXPECT_THAT(bad.out + bad.err, Not(HasSubstr("inertia method")));
}

}  // namespace
}  // namespace tumble::app
