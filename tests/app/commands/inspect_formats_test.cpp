// `tumble inspect --format urdf|sdf|mjcf|jsonl`, --frame and --scale: the inertial elements
// read back with pugixml and compared with the JSON report and the closed form.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <pugixml.hpp>

#include "app/robot/inertial_xml.hpp"
#include "support/box_files.hpp"
#include "support/inspect_run.hpp"
#include "support/run_command.hpp"

namespace tumble::app {
namespace {

using ::testing::HasSubstr;
using ::testing::IsEmpty;
using tumble::testing::BoxMesh;
using tumble::testing::run_inspect_args;

/// Numbers of an attribute or element text ("1 2 3").
std::vector<double> numbers(const char* text) {
  std::vector<double> out;
  std::istringstream in(text);
  for (std::string word; in >> word;) out.push_back(std::strtod(word.c_str(), nullptr));
  return out;
}

Eigen::Vector3d vector3(const nlohmann::json& json) {
  return {json[0].get<double>(), json[1].get<double>(), json[2].get<double>()};
}

Eigen::Matrix3d matrix3(const nlohmann::json& json) {
  Eigen::Matrix3d m;
  for (int r = 0; r < 3; ++r) m.row(r) = vector3(json[r]).transpose();
  return m;
}

class InspectFormats : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = tumble::testing::fresh_directory("inspect_formats");
    // A 0.2 x 0.3 x 0.5 box turned about (1, 2, 3) by 0.7 rad, centred at (1, -2, 0.5).
    rotation_ = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    tumble::testing::write_box_ascii_stl(file(), BoxMesh(size_, rotation_, centre_));
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string file() const { return (dir_ / "box.stl").string(); }

  /// The JSON report of the box, with extra options.
  nlohmann::json json_report(std::vector<std::string> args = {}) const {
    args.insert(args.begin(), {"--format", "json", file()});
    const auto run = run_inspect_args(args);
    EXPECT_EQ(run.status, 0) << run.err;
    return nlohmann::json::parse(run.out);
  }

  /// The element printed with `args`, parsed.
  pugi::xml_node element(pugi::xml_document& doc, std::vector<std::string> args) const {
    args.push_back(file());
    const auto run = run_inspect_args(args);
    EXPECT_EQ(run.status, 0) << run.err;
    EXPECT_TRUE(doc.load_string(run.out.c_str())) << run.out;
    return doc.child("inertial");
  }

  std::filesystem::path dir_;
  Eigen::Vector3d size_{0.2, 0.3, 0.5};
  Eigen::Vector3d centre_{1.0, -2.0, 0.5};
  Eigen::Matrix3d rotation_;
};

TEST_F(InspectFormats, ProductsOfInertiaAreTensorElementsOfTheClosedForm) {
  const nlohmann::json report = json_report();
  const double mass = 1000.0 * size_.prod();
  // The tensor R diag(I) R^T, and its products as -integral(x y dm) of the second moments
  // S = R diag(m a^2 / 12, ...) R^T (ASCII STL reaches tumble as float32: 1e-6).
  const Eigen::Matrix3d expected =
      rotation_ * tumble::testing::box_moments(mass, size_).asDiagonal() * rotation_.transpose();
  const Eigen::Matrix3d second =
      rotation_ * (mass / 12.0 * size_.cwiseProduct(size_)).asDiagonal() * rotation_.transpose();
  const Eigen::Matrix3d inertia = matrix3(report["inertia"]);
  const double tolerance = 1e-6 * expected.norm();
  EXPECT_TRUE(inertia.isApprox(expected, 1e-6)) << inertia << "\n\n" << expected;
  EXPECT_NEAR(inertia(0, 1), -second(0, 1), tolerance);
  EXPECT_NEAR(inertia(0, 2), -second(0, 2), tolerance);
  EXPECT_NEAR(inertia(1, 2), -second(1, 2), tolerance);
  EXPECT_GT(std::abs(inertia(0, 1)), 100 * tolerance);  // a real off-diagonal case

  // URDF in the mesh frame: the same numbers, exactly, rotation zero.
  pugi::xml_document doc;
  const pugi::xml_node urdf = element(doc, {"--format", "urdf"});
  const pugi::xml_node I = urdf.child("inertia");
  EXPECT_EQ(I.attribute("ixx").as_double(), inertia(0, 0));
  EXPECT_EQ(I.attribute("ixy").as_double(), inertia(0, 1));
  EXPECT_EQ(I.attribute("ixz").as_double(), inertia(0, 2));
  EXPECT_EQ(I.attribute("iyy").as_double(), inertia(1, 1));
  EXPECT_EQ(I.attribute("iyz").as_double(), inertia(1, 2));
  EXPECT_EQ(I.attribute("izz").as_double(), inertia(2, 2));
  EXPECT_EQ(urdf.child("mass").attribute("value").as_double(), report["mass"].get<double>());
  EXPECT_EQ(numbers(urdf.child("origin").attribute("xyz").value()),
            report["center_of_mass"].get<std::vector<double>>());
  EXPECT_EQ(numbers(urdf.child("origin").attribute("rpy").value()), (std::vector<double>{0, 0, 0}));
  EXPECT_TRUE(vector3(report["center_of_mass"]).isApprox(centre_, 1e-6));
}

TEST_F(InspectFormats, PrincipalFrameRpyReproducesTheTensor) {
  const Eigen::Matrix3d inertia = matrix3(json_report()["inertia"]);
  for (const char* format : {"urdf", "sdf"}) {
    pugi::xml_document doc;
    const pugi::xml_node inertial = element(doc, {"--format", format, "--frame", "principal"});
    Eigen::Vector3d rpy, moments;
    if (std::string(format) == "urdf") {
      const auto values = numbers(inertial.child("origin").attribute("rpy").value());
      ASSERT_EQ(values.size(), 3u);
      rpy = {values[0], values[1], values[2]};
      const pugi::xml_node I = inertial.child("inertia");
      moments = {I.attribute("ixx").as_double(), I.attribute("iyy").as_double(),
                 I.attribute("izz").as_double()};
      EXPECT_EQ(I.attribute("ixy").as_double(), 0.0);
    } else {
      const auto pose = numbers(inertial.child_value("pose"));
      ASSERT_EQ(pose.size(), 6u);
      rpy = {pose[3], pose[4], pose[5]};
      const pugi::xml_node I = inertial.child("inertia");
      moments = {numbers(I.child_value("ixx"))[0], numbers(I.child_value("iyy"))[0],
                 numbers(I.child_value("izz"))[0]};
      EXPECT_EQ(numbers(I.child_value("iyz"))[0], 0.0);
    }
    const Eigen::Matrix3d R = robot::rotation_from_rpy(rpy);
    const Eigen::Matrix3d rebuilt = R * moments.asDiagonal() * R.transpose();
    EXPECT_LT((rebuilt - inertia).norm(), 1e-12 * inertia.norm()) << format << "\n" << rebuilt;
  }
}

TEST_F(InspectFormats, SdfAndMjcfRoundTripExactly) {
  const nlohmann::json report = json_report();
  const Eigen::Matrix3d I = matrix3(report["inertia"]);
  pugi::xml_document sdf_doc;
  const pugi::xml_node sdf = element(sdf_doc, {"--format", "sdf"});
  const auto pose = numbers(sdf.child_value("pose"));
  ASSERT_EQ(pose.size(), 6u);
  EXPECT_EQ(Eigen::Vector3d(pose[0], pose[1], pose[2]), vector3(report["center_of_mass"]));
  EXPECT_EQ(numbers(sdf.child_value("mass"))[0], report["mass"].get<double>());
  EXPECT_EQ(numbers(sdf.child("inertia").child_value("ixy"))[0], I(0, 1));
  EXPECT_EQ(numbers(sdf.child("inertia").child_value("ixz"))[0], I(0, 2));
  EXPECT_EQ(numbers(sdf.child("inertia").child_value("iyz"))[0], I(1, 2));

  // MJCF: fullinertia in MuJoCo's order "ixx iyy izz ixy ixz iyz".
  pugi::xml_document mjcf_doc;
  const pugi::xml_node mjcf = element(mjcf_doc, {"--format", "mjcf"});
  EXPECT_EQ(numbers(mjcf.attribute("fullinertia").value()),
            (std::vector<double>{I(0, 0), I(1, 1), I(2, 2), I(0, 1), I(0, 2), I(1, 2)}));
  EXPECT_EQ(numbers(mjcf.attribute("pos").value()),
            report["center_of_mass"].get<std::vector<double>>());
  EXPECT_EQ(mjcf.attribute("mass").as_double(), report["mass"].get<double>());

  // Principal: quat is w x y z, and it turns diaginertia back into the tensor.
  pugi::xml_document principal_doc;
  const pugi::xml_node principal = element(principal_doc, {"--format=mjcf", "--frame=principal"});
  const auto q = numbers(principal.attribute("quat").value());
  const auto d = numbers(principal.attribute("diaginertia").value());
  ASSERT_EQ(q.size(), 4u);
  ASSERT_EQ(d.size(), 3u);
  const Eigen::Matrix3d R = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).toRotationMatrix();
  const Eigen::Matrix3d rebuilt =
      R * Eigen::Vector3d(d[0], d[1], d[2]).asDiagonal() * R.transpose();
  EXPECT_LT((rebuilt - I).norm(), 1e-12 * I.norm());
  EXPECT_TRUE(mjcf.attribute("quat").empty());
  EXPECT_TRUE(principal.attribute("fullinertia").empty());
}

TEST_F(InspectFormats, FrameChangesOnlyTheXmlFormats) {
  for (const char* format : {"json", "jsonl", "text"}) {
    const auto mesh = run_inspect_args({"--format", format, file()});
    const auto principal = run_inspect_args({"--format", format, "--frame", "principal", file()});
    EXPECT_EQ(mesh.out, principal.out) << format;
  }
  const auto mesh = run_inspect_args({"--format", "urdf", file()});
  const auto principal = run_inspect_args({"--format", "urdf", "--frame", "principal", file()});
  EXPECT_NE(mesh.out, principal.out);
  EXPECT_EQ(run_inspect_args({"--frame", "body", file()}).status, 1);
  EXPECT_EQ(run_inspect_args({"--format", "yaml", file()}).status, 1);
}

TEST_F(InspectFormats, SeveralFilesAreHeadedByComments) {
  tumble::testing::write_box_ascii_stl(dir_ / "a--b-.stl", BoxMesh({1, 1, 1}));
  const auto run = run_inspect_args({"--format", "urdf", file(), (dir_ / "a--b-.stl").string()});
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_EQ(run.out.find("<!-- " + file() + " -->\n<inertial>"), 0u) << run.out;
  // "--" cannot be inside a comment, nor '-' at its end.
  EXPECT_THAT(run.out, HasSubstr("a- -b-.stl -->\n<inertial>"));
  // Wrapped in one root, the output is a well-formed document with two elements.
  pugi::xml_document doc;
  ASSERT_TRUE(doc.load_string(("<robot>" + run.out + "</robot>").c_str())) << run.out;
  EXPECT_EQ(std::distance(doc.child("robot").children("inertial").begin(),
                          doc.child("robot").children("inertial").end()),
            2);
}

TEST_F(InspectFormats, NegativeScaleMirrors) {
  const nlohmann::json plain = json_report();
  const nlohmann::json mirrored = json_report({"--scale=-1,1,1"});
  EXPECT_EQ(mirrored["volume"].get<double>(), plain["volume"].get<double>());
  EXPECT_GT(mirrored["volume"].get<double>(), 0.0);
  EXPECT_EQ(mirrored["flipped"], false);
  EXPECT_THAT(mirrored["warnings"], IsEmpty());
  const Eigen::Vector3d com = vector3(plain["center_of_mass"]);
  const Eigen::Vector3d mirrored_com = vector3(mirrored["center_of_mass"]);
  EXPECT_NEAR(mirrored_com.x(), -com.x(), 1e-15);
  EXPECT_NEAR(mirrored_com.y(), com.y(), 1e-15);
  const Eigen::Matrix3d I = matrix3(plain["inertia"]);
  const Eigen::Matrix3d J = matrix3(mirrored["inertia"]);
  const double tolerance = 1e-12 * I.norm();
  EXPECT_NEAR(J(0, 1), -I(0, 1), tolerance);
  EXPECT_NEAR(J(0, 2), -I(0, 2), tolerance);
  EXPECT_NEAR(J(1, 2), I(1, 2), tolerance);
  EXPECT_NEAR(J(0, 0), I(0, 0), tolerance);
}

TEST_F(InspectFormats, ThreeScaleFactorsGiveTheScaledBox) {
  const std::string cube = (dir_ / "cube.stl").string();
  tumble::testing::write_box_ascii_stl(cube, BoxMesh({1, 1, 1}));
  const auto run = run_inspect_args({"--json", "--scale", "2,3,4", "--density", "10", cube});
  ASSERT_EQ(run.status, 0) << run.err;
  const auto report = nlohmann::json::parse(run.out);
  EXPECT_NEAR(report["volume"].get<double>(), 24.0, 1e-12);
  const Eigen::Vector3d moments = tumble::testing::box_moments(240.0, {2, 3, 4});
  const Eigen::Matrix3d I = matrix3(report["inertia"]);
  EXPECT_LT((I - Eigen::Matrix3d(moments.asDiagonal())).norm(), 1e-12 * moments.norm());
}

TEST_F(InspectFormats, BadScalesAreRefusedInOneLine) {
  for (const char* scale : {"0", "1,2", "nan", "1,0,1", "1,,1", "1,2,3,4", "x", "inf"}) {
    const auto run = tumble::testing::run_command(tumble::testing::tumble_executable() +
                                                  " inspect --scale=" + scale + " " + file());
    EXPECT_EQ(run.status, 1) << scale;
    EXPECT_THAT(run.err, HasSubstr("--scale: expected one factor or three (sx,sy,sz)")) << scale;
    EXPECT_THAT(run.err, HasSubstr(std::string("got \"") + scale + "\"")) << scale;
    EXPECT_TRUE(run.out.empty());
  }
  EXPECT_EQ(parse_scale_factors("+0.001"), Eigen::Vector3d::Constant(0.001));
  EXPECT_EQ(parse_scale_factors("1,-2,1e-3"), Eigen::Vector3d(1, -2, 0.001));
}

TEST_F(InspectFormats, HelpNamesTheNewOptions) {
  const auto help =
      tumble::testing::run_command(tumble::testing::tumble_executable() + " inspect --help");
  EXPECT_EQ(help.status, 0);
  for (const char* option : {"--format", "--frame", "--jsonl", "--jobs", "--recursive", "@LIST",
                             "sx,sy,sz", "json has both and ignores it"}) {
    EXPECT_THAT(help.out, HasSubstr(option));
  }
}

TEST_F(InspectFormats, JsonlPrintsAnErrorObjectAndGoesOn) {
  const std::string bad = (dir_ / "missing.stl").string();
  const auto run = run_inspect_args({"--jsonl", file(), bad, file()});
  EXPECT_EQ(run.status, 1);
  std::istringstream lines(run.out);
  std::vector<nlohmann::json> objects;
  for (std::string line; std::getline(lines, line);) objects.push_back(nlohmann::json::parse(line));
  ASSERT_EQ(objects.size(), 3u) << run.out;
  EXPECT_EQ(objects[0]["file"], file());
  EXPECT_TRUE(objects[0].contains("inertia"));
  EXPECT_EQ(objects[1], (nlohmann::json{{"file", bad}, {"error", "no such file"}}));
  EXPECT_EQ(objects[2], objects[0]);
  EXPECT_THAT(run.err, HasSubstr("tumble inspect: error: " + bad + ": no such file\n"));
  EXPECT_THAT(run.err, HasSubstr("inspected 3 files: 2 ok, 0 with warnings, 1 refused\n"));
}

}  // namespace
}  // namespace tumble::app
