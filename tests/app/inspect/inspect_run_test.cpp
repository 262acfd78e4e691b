// `tumble inspect` as library calls (app/inspect/inspect_run.hpp): inspect_files' reports
// against the closed-form box, its errors, and inspect_json against the command's --json.
#include "app/inspect/inspect_run.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "support/box_files.hpp"
#include "support/command_test.hpp"
#include "support/inspect_run.hpp"

namespace tumble::app {
namespace {

using ::testing::HasSubstr;

class InspectLibrary : public testing::CommandTest {};

TEST_F(InspectLibrary, FilesGiveReportsInInputOrderAndErrorsInTheirPlace) {
  const Eigen::Vector3d size(0.1, 0.2, 0.4);
  testing::write_box_binary_stl(dir_ / "a.stl", testing::BoxMesh(size));
  testing::write_box_obj(dir_ / "b.obj", testing::BoxMesh(2.0 * size));
  std::ofstream(dir_ / "broken.stl") << "solid nothing\n";
  InspectOptions options;
  options.files = {dir_ / "b.obj", dir_ / "broken.stl", dir_ / "a.stl"};
  options.jobs = 2;
  const std::vector<InspectResult> results = inspect_files(options);
  ASSERT_EQ(results.size(), 3u);
  EXPECT_EQ(results[0].file, dir_ / "b.obj");
  EXPECT_EQ(results[1].file, dir_ / "broken.stl");
  EXPECT_EQ(results[2].file, dir_ / "a.stl");
  ASSERT_TRUE(results[0].report);
  ASSERT_TRUE(results[2].report);
  EXPECT_FALSE(results[1].report);
  EXPECT_THAT(results[1].error, HasSubstr((dir_ / "broken.stl").string()));
  // Density 1000 kg/m^3 (water): mass = 1000 abc, moments m (b^2 + c^2) / 12 and so on; the
  // files hold single-precision coordinates (0.1 is not a float), hence 1e-6 relative.
  const double mass = 1000.0 * size.prod();
  EXPECT_NEAR(results[2].report->volume, size.prod(), 1e-6 * size.prod());
  EXPECT_NEAR(results[2].report->mass_properties.mass, mass, 1e-6 * mass);
  const Eigen::Vector3d moments = testing::box_moments(mass, size);
  const Eigen::Matrix3d& inertia = results[2].report->mass_properties.inertia;
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(inertia(i, i), moments[i], 1e-6 * moments[i]);
  EXPECT_NEAR(results[0].report->volume, 8.0 * size.prod(), 1e-6 * size.prod());
}

TEST_F(InspectLibrary, JsonOfAReportIsWhatTheCommandPrints) {
  testing::write_box_ascii_stl(dir_ / "box.stl", testing::BoxMesh({0.3, 0.2, 0.1}));
  InspectOptions options;
  options.files = {dir_ / "box.stl"};
  const std::vector<InspectResult> results = inspect_files(options);
  ASSERT_EQ(results.size(), 1u);
  ASSERT_TRUE(results[0].report) << results[0].error;
  const testing::InspectRun command =
      testing::run_inspect_args({(dir_ / "box.stl").string(), "--json"});
  ASSERT_EQ(command.status, 0) << command.err;
  EXPECT_EQ(inspect_json(*results[0].report).dump(2) + "\n", command.out);
}

TEST_F(InspectLibrary, DirectoryExpandsToItsMeshFilesSorted) {
  testing::write_box_binary_stl(dir_ / "z.stl", testing::BoxMesh({1, 1, 1}));
  testing::write_box_binary_stl(dir_ / "m.stl", testing::BoxMesh({1, 2, 1}));
  std::ofstream(dir_ / "notes.txt") << "not a mesh\n";
  InspectOptions options;
  options.files = {dir_};
  const std::vector<InspectResult> results = inspect_files(options);
  ASSERT_EQ(results.size(), 2u);
  EXPECT_EQ(results[0].file.filename(), "m.stl");
  EXPECT_EQ(results[1].file.filename(), "z.stl");
  ASSERT_TRUE(results[0].report);
  EXPECT_NEAR(results[0].report->volume, 2.0, 1e-6);
}

}  // namespace
}  // namespace tumble::app
