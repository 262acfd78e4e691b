// End-to-end tests of `tumble inspect`: the executable, its output and its errors.
#include "app/commands/inspect_command.hpp"
#include "app/scene/mesh_inspection.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include <nlohmann/json.hpp>

#include "support/run_command.hpp"
#include "support/stl_writer.hpp"

namespace tumble::app {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
using tumble::testing::fresh_directory;
using tumble::testing::run_command;
using tumble::testing::tumble_executable;

/// An ASCII STL solid of an axis-aligned box with the given size and centre; `skip_faces`
/// leaves out the last triangles (to make it open).
std::string box_solid(double sx, double sy, double sz, double cx = 0, double cy = 0, double cz = 0,
                      int skip_faces = 0) {
  const double x[2] = {cx - sx / 2, cx + sx / 2}, y[2] = {cy - sy / 2, cy + sy / 2},
               z[2] = {cz - sz / 2, cz + sz / 2};
  const auto corner = [&](int i) {
    return Eigen::Vector3d(x[i & 1], y[(i >> 1) & 1], z[(i >> 2) & 1]);
  };
  // Outward-wound quads of the unit cube's corner numbering (bit 0 = x, 1 = y, 2 = z), two
  // triangles each.
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  const auto triangle = [&](std::size_t i) {
    const int* q = quads[i / 2];
    const int second = i % 2 == 0 ? 1 : 2;
    return testing::StlTriangle{Eigen::Vector3d::Zero(), corner(q[0]), corner(q[second]),
                                corner(q[second + 1])};
  };
  return testing::ascii_stl_solid("box", 12 - skip_faces, triangle);
}

void write_box_stl(const std::filesystem::path& file, double sx, double sy, double sz,
                   double cx = 0, double cy = 0, double cz = 0, int skip_faces = 0) {
  testing::write_stl_file(file, box_solid(sx, sy, sz, cx, cy, cz, skip_faces));
}

class InspectCommand : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = fresh_directory("inspect"); }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::filesystem::path dir_;
};

TEST_F(InspectCommand, HelpListsEveryOption) {
  const auto top = run_command(tumble_executable() + " --help");
  EXPECT_EQ(top.status, 0);
  EXPECT_THAT(top.out, HasSubstr("inspect"));
  const auto help = run_command(tumble_executable() + " inspect --help");
  EXPECT_EQ(help.status, 0);
  for (const char* option : {"--density", "--mass", "--scale", "--shell", "--json", "MESH"}) {
    EXPECT_THAT(help.out, HasSubstr(option));
  }
}

TEST_F(InspectCommand, JsonReportOfABoxMatchesTheClosedForm) {
  // A 2 x 3 x 4 box centred at (1, 2, 3), density 500: m = 12000, Ixx = m (9 + 16) / 12.
  write_box_stl(path("box.stl"), 2, 3, 4, 1, 2, 3);
  const auto result =
      run_command(tumble_executable() + " inspect --json --density 500 " + path("box.stl"));
  ASSERT_EQ(result.status, 0) << result.err;
  const auto json = nlohmann::json::parse(result.out);
  for (const char* key :
       {"file", "triangles", "parts", "watertight", "volume", "mass", "density", "center_of_mass",
        "inertia", "principal_moments", "principal_axes", "warnings"}) {
    EXPECT_TRUE(json.contains(key)) << key;
  }
  const double m = 24.0 * 500.0;
  EXPECT_EQ(json["file"], path("box.stl"));
  EXPECT_EQ(json["triangles"], 12);
  EXPECT_EQ(json["vertices"], 8);          // 36 STL corners welded on import
  EXPECT_EQ(json["welded_vertices"], 28);  // (the analysis then need not weld again)
  EXPECT_EQ(json["parts"], 1);
  EXPECT_EQ(json["watertight"], true);
  EXPECT_NEAR(json["volume"].get<double>(), 24.0, 1e-12);
  EXPECT_NEAR(json["mass"].get<double>(), m, 1e-9);
  EXPECT_NEAR(json["density"].get<double>(), 500.0, 0);
  const std::array<double, 3> com = {1, 2, 3};
  const std::array<double, 3> moments = {m * (9 + 16) / 12, m * (4 + 16) / 12, m * (4 + 9) / 12};
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(json["center_of_mass"][i].get<double>(), com[i], 1e-12);
    EXPECT_NEAR(json["inertia"][i][i].get<double>(), moments[i], 1e-9 * moments[0]);
    for (int j = 0; j < 3; ++j) {
      if (i != j) {
        EXPECT_NEAR(json["inertia"][i][j].get<double>(), 0.0, 1e-9 * moments[0]);
      }
    }
  }
  // Principal moments ascending: z (13), y (20), x (25); axes are their columns.
  EXPECT_NEAR(json["principal_moments"][0].get<double>(), moments[2], 1e-9 * moments[0]);
  EXPECT_NEAR(json["principal_moments"][2].get<double>(), moments[0], 1e-9 * moments[0]);
  EXPECT_NEAR(std::abs(json["principal_axes"][2][0].get<double>()), 1.0, 1e-12);
  EXPECT_NEAR(std::abs(json["principal_axes"][0][2].get<double>()), 1.0, 1e-12);
  EXPECT_TRUE(json["warnings"].empty());
}

TEST_F(InspectCommand, MassAndScaleOptions) {
  // Millimetres: a 20 x 30 x 40 mm box of total mass 2 kg.
  write_box_stl(path("mm.stl"), 20, 30, 40);
  const auto result =
      run_command(tumble_executable() + " inspect --json --scale 0.001 --mass 2 " + path("mm.stl"));
  ASSERT_EQ(result.status, 0) << result.err;
  const auto json = nlohmann::json::parse(result.out);
  EXPECT_NEAR(json["volume"].get<double>(), 24e-6, 1e-18);
  EXPECT_NEAR(json["mass"].get<double>(), 2.0, 1e-12);
  EXPECT_NEAR(json["density"].get<double>(), 2.0 / 24e-6, 1e-6);
  EXPECT_NEAR(json["principal_moments"][2].get<double>(), 2.0 * (0.03 * 0.03 + 0.04 * 0.04) / 12,
              1e-15);
}

TEST_F(InspectCommand, SeveralFilesGiveAJsonArray) {
  write_box_stl(path("a.stl"), 1, 1, 1);
  write_box_stl(path("b.stl"), 2, 2, 2);
  const auto result =
      run_command(tumble_executable() + " inspect --json " + path("a.stl") + " " + path("b.stl"));
  ASSERT_EQ(result.status, 0) << result.err;
  const auto json = nlohmann::json::parse(result.out);
  ASSERT_TRUE(json.is_array());
  ASSERT_EQ(json.size(), 2u);
  EXPECT_NEAR(json[0]["volume"].get<double>(), 1.0, 1e-12);
  EXPECT_NEAR(json[1]["volume"].get<double>(), 8.0, 1e-12);
}

TEST_F(InspectCommand, HumanReportShowsTheTable) {
  write_box_stl(path("box.stl"), 2, 3, 4);
  const auto result = run_command(tumble_executable() + " inspect " + path("box.stl"));
  ASSERT_EQ(result.status, 0) << result.err;
  for (const char* label : {"triangles", "volume", "mass", "centre of mass", "inertia",
                            "principal moments", "principal axes", "checks", "closed surface"}) {
    EXPECT_THAT(result.out, HasSubstr(label));
  }
  EXPECT_THAT(result.out, HasSubstr("24000 kg"));
  EXPECT_TRUE(result.err.empty()) << result.err;
}

TEST_F(InspectCommand, OpenMeshFailsWithOneLineNamingTheFile) {
  write_box_stl(path("open.stl"), 1, 1, 1, 0, 0, 0, /*skip_faces=*/2);
  const auto result = run_command(tumble_executable() + " inspect " + path("open.stl"));
  EXPECT_EQ(result.status, 1);
  EXPECT_THAT(result.err, HasSubstr(path("open.stl")));
  EXPECT_THAT(result.err, HasSubstr("4 boundary edges"));
  EXPECT_THAT(result.err, HasSubstr("--shell"));
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  EXPECT_TRUE(result.out.empty());
}

TEST_F(InspectCommand, OverlappingPartsAreTheirUnionTheirSumOrRefused) {
  // Two unit cubes, the second moved by (0.5, 0.5, 0.5): they share 0.125 m^3, so their union
  // is 2 - 0.125 = 1.875 m^3 (inclusion-exclusion).
  testing::write_stl_file(path("two.stl"), box_solid(1, 1, 1) + box_solid(1, 1, 1, 0.5, 0.5, 0.5));
  const auto refused =
      run_command(tumble_executable() + " inspect --overlap refuse " + path("two.stl"));
  EXPECT_EQ(refused.status, 1);
  EXPECT_EQ(refused.err, "tumble inspect: error: " + path("two.stl") +
                             ": parts 1 and 2 of 2 overlap (their surfaces cross), so their "
                             "shared volume (0.125 m^3) would count twice; give --overlap union "
                             "to take their exact union or --overlap sum to count each part "
                             "whole (\"overlap\" in a scene)\n");
  EXPECT_TRUE(refused.out.empty());

  for (const char* sum : {"--overlap sum", "--allow-overlap"}) {
    const auto allowed =
        run_command(tumble_executable() + " inspect " + sum + " --json " + path("two.stl"));
    ASSERT_EQ(allowed.status, 0) << allowed.err;
    const nlohmann::json report = nlohmann::json::parse(allowed.out);
    EXPECT_NEAR(report.at("volume").get<double>(), 2.0, 1e-12);  // both cubes, as warned
    EXPECT_EQ(report.at("overlap"), "sum");
    EXPECT_THAT(report.at("warnings").dump(), HasSubstr("shared volume (0.125 m^3) counts twice"));
  }
  const auto human = run_command(tumble_executable() + " inspect --overlap sum " + path("two.stl"));
  EXPECT_THAT(human.out, HasSubstr("note  parts 1 and 2 of 2 overlap"));
  EXPECT_THAT(human.out, HasSubstr("overlap           sum\n"));

  // The default: their exact union, the shared volume stated.
  const auto united = run_command(tumble_executable() + " inspect --json " + path("two.stl"));
  ASSERT_EQ(united.status, 0) << united.err;
  const nlohmann::json report = nlohmann::json::parse(united.out);
  EXPECT_NEAR(report.at("volume").get<double>(), 1.875, 1e-12);
  EXPECT_EQ(report.at("overlap"), "union");
  EXPECT_EQ(report.at("united_parts"), 2);
  EXPECT_NEAR(report.at("shared_volume").get<double>(), 0.125, 1e-12);
  EXPECT_THAT(report.at("warnings").dump(),
              HasSubstr("parts 1 and 2 of 2 are taken as their exact union (--overlap union): "
                        "their shared volume, counted once, is 0.125 m^3 (6.66667% of the "
                        "mesh's volume)"));
  const auto text = run_command(tumble_executable() + " inspect " + path("two.stl"));
  EXPECT_THAT(text.out, HasSubstr("overlap           union of 2 parts, shared volume 0.125 m^3 "
                                  "counted once"));
  const auto bad = run_command(tumble_executable() + " inspect --overlap merge " + path("two.stl"));
  EXPECT_EQ(bad.status, 1);
  EXPECT_THAT(bad.err, HasSubstr("--overlap"));
}

TEST_F(InspectCommand, SkippingTheOverlapChecksChangesNoCleanResultAndStillSeesNesting) {
  // Two separate cubes: the same report, byte for byte.
  testing::write_stl_file(path("apart.stl"), box_solid(1, 1, 1) + box_solid(1, 1, 1, 3, 0, 0));
  const auto checked = run_command(tumble_executable() + " inspect --json " + path("apart.stl"));
  const auto skipped = run_command(tumble_executable() + " inspect --skip-overlap-checks --json " +
                                   path("apart.stl"));
  ASSERT_EQ(skipped.status, 0) << skipped.err;
  EXPECT_EQ(skipped.out, checked.out);
  EXPECT_NEAR(nlohmann::json::parse(skipped.out).at("volume").get<double>(), 2.0, 1e-12);
  // A cube inside a larger one, facing the same way: containment is still decided.
  testing::write_stl_file(path("nested.stl"),
                          box_solid(2, 2, 2) + box_solid(0.5, 0.5, 0.5, 0.25, 0.25, 0.25));
  const auto nested =
      run_command(tumble_executable() + " inspect --skip-overlap-checks --overlap refuse " +
                  path("nested.stl"));
  EXPECT_EQ(nested.status, 1);
  EXPECT_THAT(nested.err, HasSubstr("lies inside another part with the same orientation"));
  // By default the inner cube is inside the union: the outer cube alone.
  const auto united = run_command(tumble_executable() + " inspect --skip-overlap-checks --json " +
                                  path("nested.stl"));
  ASSERT_EQ(united.status, 0) << united.err;
  EXPECT_NEAR(nlohmann::json::parse(united.out).at("volume").get<double>(), 8.0, 1e-12);
}

TEST_F(InspectCommand, PartsStackedFaceToFaceAreNoOverlap) {
  testing::write_stl_file(path("stack.stl"),
                          box_solid(1, 1, 1) + box_solid(0.5, 0.5, 0.5, 0, 0, 0.75));
  const auto result = run_command(tumble_executable() + " inspect --json " + path("stack.stl"));
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_NEAR(nlohmann::json::parse(result.out).at("volume").get<double>(), 1.125, 1e-6);
}

TEST_F(InspectCommand, ShellModeAcceptsTheOpenMesh) {
  // The box without its top face (two triangles at z = +0.5), as a 1 mm sheet.
  write_box_stl(path("open.stl"), 1, 1, 1, 0, 0, 0, 2);
  const auto result =
      run_command(tumble_executable() + " inspect --json --shell 0.001 " + path("open.stl"));
  ASSERT_EQ(result.status, 0) << result.err;
  const auto json = nlohmann::json::parse(result.out);
  EXPECT_EQ(json["shell"], true);
  EXPECT_EQ(json["watertight"], false);
  EXPECT_NEAR(json["area"].get<double>(), 5.0, 1e-12);
  EXPECT_NEAR(json["mass"].get<double>(), 5.0 * 0.001 * 1000.0, 1e-9);
}

TEST_F(InspectCommand, MissingFileAndBadValuesAreErrors) {
  const auto missing = run_command(tumble_executable() + " inspect " + path("nope.stl"));
  EXPECT_EQ(missing.status, 1);
  EXPECT_THAT(missing.err, HasSubstr(path("nope.stl") + ": no such file"));

  write_box_stl(path("box.stl"), 1, 1, 1);
  const auto negative =
      run_command(tumble_executable() + " inspect --density -3 " + path("box.stl"));
  EXPECT_NE(negative.status, 0);
  EXPECT_THAT(negative.err, HasSubstr("density must be a positive finite number"));

  const auto both =
      run_command(tumble_executable() + " inspect --density 3 --mass 1 " + path("box.stl"));
  EXPECT_NE(both.status, 0);
  EXPECT_THAT(both.err, HasSubstr("excludes"));

  const auto nan_scale =
      run_command(tumble_executable() + " inspect --scale nan " + path("box.stl"));
  EXPECT_NE(nan_scale.status, 0);
  EXPECT_THAT(nan_scale.err, HasSubstr("scale"));
}

TEST_F(InspectCommand, OneBadFileAmongGoodOnesFailsAndJsonPrintsNothing) {
  write_box_stl(path("good.stl"), 1, 1, 1);
  const auto human =
      run_command(tumble_executable() + " inspect " + path("good.stl") + " " + path("bad.stl"));
  EXPECT_EQ(human.status, 1);
  EXPECT_THAT(human.out, HasSubstr("good.stl"));
  EXPECT_THAT(human.err, HasSubstr("bad.stl: no such file"));
  const auto json = run_command(tumble_executable() + " inspect --json " + path("good.stl") + " " +
                                path("bad.stl"));
  EXPECT_EQ(json.status, 1);
  EXPECT_TRUE(json.out.empty());
}

}  // namespace
}  // namespace tumble::app
