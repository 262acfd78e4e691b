// The unit hint of `tumble inspect`: which sizes get one, and what it says.
#include "app/scene/unit_hint.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "support/box_files.hpp"
#include "support/inspect_run.hpp"
#include "support/run_command.hpp"

namespace tumble::app {
namespace {

using ::testing::HasSubstr;
using ::testing::Optional;

engine::MeshReport sized(const Eigen::Vector3d& size) {
  engine::MeshReport report;
  report.bounds_min = -0.5 * size;
  report.bounds_max = 0.5 * size;
  return report;
}

const Eigen::Vector3d kOnes = Eigen::Vector3d::Ones();

TEST(InspectUnitHint, MillimetresAndInchesForLargeBodies) {
  EXPECT_THAT(
      unit_hint(sized({111, 40, 20}), kOnes),
      Optional(std::string("size 111 m: millimetres? --scale 0.001; inches? --scale 0.0254")));
  // 2000 m is 50.8 m in inches: only millimetres fit.
  EXPECT_THAT(unit_hint(sized({2000, 1, 1}), kOnes),
              Optional(std::string("size 2000 m: millimetres? --scale 0.001")));
  // 5e6 m: micrometres (5 m).
  EXPECT_THAT(unit_hint(sized({5e6, 1, 1}), kOnes),
              Optional(std::string("size 5e+06 m: micrometres? --scale 1e-06")));
  // 1e12 m fits none: no guess.
  EXPECT_EQ(unit_hint(sized({1e12, 1, 1}), kOnes), std::nullopt);
  // A mirror is no scale; any other factor is the user's choice.
  EXPECT_TRUE(unit_hint(sized({111, 1, 1}), {-1, 1, 1}).has_value());
  EXPECT_EQ(unit_hint(sized({111, 1, 1}), {0.5, 0.5, 0.5}), std::nullopt);
}

TEST(InspectUnitHint, OrdinarySizesGetNone) {
  for (const double length : {0.001, 0.05, 1.0, 10.0}) {
    EXPECT_EQ(unit_hint(sized({length, length / 2, length / 3}), kOnes), std::nullopt) << length;
  }
  EXPECT_EQ(unit_hint(sized({0.1, 0.1, 0.1}), Eigen::Vector3d::Constant(0.001)), std::nullopt);
}

TEST(InspectUnitHint, TinyBodies) {
  // 0.2 mm after --scale 0.001: the file's 0.2 was metres already.
  EXPECT_THAT(unit_hint(sized({2e-4, 1e-4, 1e-4}), Eigen::Vector3d::Constant(0.001)),
              Optional(std::string("size 0.2 mm: the file may already be in metres: leave out "
                                   "--scale")));
  EXPECT_THAT(unit_hint(sized({5e-4, 1e-4, 1e-4}), kOnes),
              Optional(std::string(
                  "size 0.5 mm: under a millimetre; if the file is not in metres, give --scale")));
  // Tiny in the file too: nothing to suggest.
  EXPECT_EQ(unit_hint(sized({2e-7, 1e-7, 1e-7}), Eigen::Vector3d::Constant(0.001)), std::nullopt);
}

TEST(InspectUnitHint, TheCommandAddsItToTheWarnings) {
  const auto dir = tumble::testing::fresh_directory("unit_hint");
  const std::string file = (dir / "part_mm.stl").string();
  tumble::testing::write_box_binary_stl(file, tumble::testing::BoxMesh({111, 40, 20}));
  const auto text = tumble::testing::run_inspect_args({file});
  EXPECT_EQ(text.status, 0) << text.err;
  EXPECT_THAT(text.out, HasSubstr("note  size 111 m: millimetres? --scale 0.001"));
  const auto scaled = tumble::testing::run_inspect_args({"--json", "--scale", "0.001", file});
  EXPECT_EQ(nlohmann::json::parse(scaled.out)["warnings"], nlohmann::json::array());
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace tumble::app
