// A robot file as a picture (`tumble render ROBOT -o robot.png`): the links' boxes against
// closed forms, the verdicts against `tumble inertials`' tolerance, picking, and the still
// image by its properties (its size, and the colours of the boxes where they must be).
#include "app/video/robot_picture.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "app/video/robot_render.hpp"
#include "media/png_io.hpp"
#include "render/camera_math.hpp"
#include "support/command_test.hpp"
#include "support/input_error.hpp"
#include "support/run_command.hpp"
#include "support/two_link_robot.hpp"

namespace tumble::app {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using tumble::testing::run_command;
using tumble::testing::tumble_executable;

/// Pixels of `image` passing `test(r, g, b)`: all, or those within `radius` of pixel
/// (`cx`, `cy`) when a radius is given.
template <typename Test>
std::size_t robot_pixels(const tumble::Image& image, Test test, int cx = 0, int cy = 0,
                         int radius = -1) {
  std::size_t count = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      if (radius >= 0 && (x - cx) * (x - cx) + (y - cy) * (y - cy) > radius * radius) continue;
      const std::size_t i = 4 * (static_cast<std::size_t>(y) * image.width + x);
      count += test(int{image.rgba[i]}, int{image.rgba[i + 1]}, int{image.rgba[i + 2]}) ? 1 : 0;
    }
  }
  return count;
}

/// The computed inertial's wire: orange (red high, blue low).
bool wire_orange(int r, int g, int b) {
  return r > 200 && g > 90 && g < 190 && b < 90;
}
/// The differing link's red box over grey: red well above green and blue.
bool box_red(int r, int g, int b) {
  return r > 130 && r - g > 60 && r - b > 60 && !wire_orange(r, g, b);
}
/// The right link's blue box: blue well above red.
bool box_blue(int r, int, int b) {
  return b - r > 60;
}

class RobotPictureTest : public testing::CommandTest {
 protected:
  void SetUp() override {
    CommandTest::SetUp();
    robot_ = dir_ / "two_link.urdf";
    std::ofstream(robot_) << testing::kTwoLinkUrdf;
  }
  fs::path robot_;
};

TEST_F(RobotPictureTest, BoxesAreTheLinksOwnAndOnlyTheWrongLinkDiffers) {
  const RobotPicture picture = load_robot_picture(robot_, {});
  ASSERT_EQ(picture.links.size(), 2u);
  const LinkPicture& base = picture.links[0];
  const LinkPicture& arm = picture.links[1];
  EXPECT_EQ(base.name, "base");
  EXPECT_EQ(base.drawn_from, "visual");
  EXPECT_EQ(arm.drawn_from, "collision");  // the arm has no visual
  EXPECT_FALSE(base.differs);
  EXPECT_TRUE(arm.differs);
  EXPECT_EQ(picture.differing(), 1u);

  // A uniform box's equal-inertia box is the box itself: sides longest first (ascending
  // moments), at its centre, both from the stated and the computed inertial.
  ASSERT_TRUE(base.stated && base.computed);
  for (const InertiaBox* box : {&*base.stated, &*base.computed}) {
    EXPECT_NEAR((box->sides - testing::kTwoLinkBaseSize).norm(), 0.0, 1e-9);
    EXPECT_NEAR((box->center - testing::kTwoLinkBaseCenter).norm(), 0.0, 1e-12);
  }
  // The cylinder's computed box: along z, sqrt(6 (2 Ixx - Izz) / m) = 0.5 m long (the
  // cylinder's length); across, sqrt(6 Izz / m) = sqrt(3/400) m. The stated 0.01 I is a cube
  // of sqrt(0.06) m.
  ASSERT_TRUE(arm.stated && arm.computed);
  EXPECT_NEAR(arm.computed->sides[0], 0.5, 1e-9);
  EXPECT_NEAR(std::abs(arm.computed->axes.col(0).z()), 1.0, 1e-9);
  EXPECT_NEAR(arm.computed->sides[1], std::sqrt(3.0 / 400.0), 1e-9);
  EXPECT_NEAR((arm.computed->center - testing::kTwoLinkArmCenter).norm(), 0.0, 1e-12);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(arm.stated->sides[i], std::sqrt(0.06), 1e-12);

  // Geometry: the base box's 8 corners within the bounds, the bounds framing both links.
  EXPECT_TRUE(picture.bounds.contains(Eigen::Vector3d(-0.2, -0.15, 0.0)));
  EXPECT_TRUE(picture.bounds.contains(Eigen::Vector3d(0.5, 0.0, 0.5)));
  // The inspector: both inertials and their differences, the verdict at the tolerance.
  const std::string text = link_inspector_text(picture, 1);
  EXPECT_THAT(text, HasSubstr("link 'arm'"));
  EXPECT_THAT(text, HasSubstr("relative difference"));
  EXPECT_THAT(text, HasSubstr("differ by more than 0.001"));
  EXPECT_THAT(text, HasSubstr("equal-inertia box, computed: 0.5 x"));
  EXPECT_THAT(link_inspector_text(picture, 0), HasSubstr("every link is within 0.001"));
}

TEST_F(RobotPictureTest, LinksArePlacedByTheirZeroConfigurationFrames) {
  // The joint lifts the arm by 1 m and turns it a quarter about z: its geometry and both boxes
  // follow, the arm's centre going from (0.5, 0, 0.25) to (0, 0.5, 1.25).
  std::string text = testing::kTwoLinkUrdf;
  const std::string joint_origin = R"(<origin xyz="0 0 0"/>)";
  text.replace(text.find(joint_origin), joint_origin.size(),
               R"(<origin xyz="0 0 1" rpy="0 0 1.5707963267948966"/>)");
  const fs::path moved = dir_ / "moved.urdf";
  std::ofstream(moved) << text;
  const RobotPicture picture = load_robot_picture(moved, {});
  ASSERT_EQ(picture.links.size(), 2u);
  const LinkPicture& arm = picture.links[1];
  const Eigen::Vector3d center(0.0, 0.5, 1.25);
  ASSERT_TRUE(arm.stated && arm.computed);
  EXPECT_NEAR((arm.computed->center - center).norm(), 0.0, 1e-12);
  EXPECT_NEAR((arm.stated->center - center).norm(), 0.0, 1e-12);
  EXPECT_NEAR(std::abs(arm.computed->axes.col(0).z()), 1.0, 1e-9);
  Eigen::AlignedBox3d geometry;
  for (const Eigen::Vector3d& p : arm.geometry.positions) geometry.extend(p);
  EXPECT_NEAR((geometry.center() - center).norm(), 0.0, 1e-9);
  EXPECT_NEAR(geometry.sizes().z(), 0.5, 1e-12);
  // The base, the root, stays where it was; the verdicts do not move with the frames.
  EXPECT_NEAR((picture.links[0].computed->center - testing::kTwoLinkBaseCenter).norm(), 0.0, 1e-12);
  EXPECT_EQ(picture.differing(), 1u);
}

TEST_F(RobotPictureTest, AClickOnALinkPicksIt) {
  const RobotPicture picture = load_robot_picture(robot_, {});
  const render::Camera camera = robot_camera(picture, 320, 240);
  for (const auto& [center, link] :
       {std::pair{testing::kTwoLinkBaseCenter, 0u}, std::pair{testing::kTwoLinkArmCenter, 1u}}) {
    const Eigen::Vector3f pixel = render::project_to_pixels(camera, 320, 240, center.cast<float>());
    EXPECT_EQ(pick_link(picture, camera, 320, 240, pixel.x(), pixel.y()), link);
  }
  EXPECT_EQ(pick_link(picture, camera, 320, 240, 1.0f, 1.0f), std::nullopt);  // a corner: sky
}

TEST_F(RobotPictureTest, RendersOneStillPngFramingTheRobot) {
  const fs::path png = dir_ / "robot.png";
  const auto result = run_command(tumble_executable() + " render '" + robot_.string() + "' -o '" +
                                  png.string() + "' --size 320x240 --no-overlay");
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("2 links, 1 differing"));
  const tumble::Image image = media::read_png(png);
  ASSERT_EQ(image.width, 320);
  ASSERT_EQ(image.height, 240);

  // Each box's colour where its link is, the wire on both; the framing keeps the robot
  // inside the image (no robot pixel on the border rows) and big (a tenth of it or more).
  const RobotPicture picture = load_robot_picture(robot_, {});
  const render::Camera camera = robot_camera(picture, 320, 240);
  const auto at = [&](const Eigen::Vector3d& p) {
    return render::project_to_pixels(camera, 320, 240, p.cast<float>());
  };
  const Eigen::Vector3f base = at(testing::kTwoLinkBaseCenter);
  const Eigen::Vector3f arm = at(testing::kTwoLinkArmCenter);
  const auto x = [](const Eigen::Vector3f& p) { return static_cast<int>(p.x()); };
  const auto y = [](const Eigen::Vector3f& p) { return static_cast<int>(p.y()); };
  EXPECT_GT(robot_pixels(image, box_blue, x(base), y(base), 12), 200u);
  // (At most a few red pixels there: the filtered edges of the orange wire.)
  EXPECT_LT(robot_pixels(image, box_red, x(base), y(base), 12), 20u);
  EXPECT_GT(robot_pixels(image, box_red, x(arm), y(arm), 8), 50u);
  EXPECT_GT(robot_pixels(image, wire_orange), 150u);
  const auto not_background = [](int r, int g, int b) {
    return box_red(r, g, b) || box_blue(r, g, b) || wire_orange(r, g, b);
  };
  EXPECT_GT(robot_pixels(image, not_background), 320u * 240u / 10u);
  for (int column = 0; column < 320; ++column) {
    for (const int row : {0, 239}) {
      const std::size_t i = 4 * (static_cast<std::size_t>(row) * 320 + column);
      EXPECT_FALSE(not_background(image.rgba[i], image.rgba[i + 1], image.rgba[i + 2]))
          << column << "," << row;
    }
  }
}

TEST_F(RobotPictureTest, BadInputIsOneLineAndNoPng) {
  const fs::path png = dir_ / "robot.png";
  // A mesh that is not there, through the command: exit 1, one line naming it, no PNG.
  std::string text = testing::kTwoLinkUrdf;
  const std::string cylinder = R"(<cylinder radius="0.05" length="0.5"/>)";
  text.replace(text.find(cylinder), cylinder.size(), R"(<mesh filename="missing_arm.stl"/>)");
  const fs::path missing = dir_ / "missing.urdf";
  std::ofstream(missing) << text;
  const auto result = run_command(tumble_executable() + " render '" + missing.string() + "' -o '" +
                                  png.string() + "' --size 64x48");
  EXPECT_EQ(result.status, 1);
  EXPECT_THAT(result.err, HasSubstr("missing_arm.stl"));
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1);

  // Malformed XML, an output that is not a PNG, a video's option: the job refuses them.
  const auto refusal = [&](const fs::path& robot, const fs::path& output,
                           std::optional<double> fps = std::nullopt) {
    RenderOptions options;
    options.scene = robot;
    options.output = output;
    options.fps = fps;
    std::ostringstream out;
    return testing::input_error_of([&] { write_robot_render(options, out); });
  };
  const fs::path broken = dir_ / "broken.urdf";
  std::ofstream(broken) << "<robot name='x'><link name='a'>";
  EXPECT_THAT(refusal(broken, png), HasSubstr("broken.urdf"));
  EXPECT_THAT(refusal(robot_, dir_ / "robot.mp4"),
              HasSubstr("a robot file renders to one .png image"));
  EXPECT_THAT(refusal(robot_, png, 10.0),
              HasSubstr("--fps: a robot file renders to one still image"));
  // Nothing written, nothing half-written left beside the output either.
  for (const std::string& entry : testing::directory_entries(dir_)) {
    EXPECT_THAT(entry, ::testing::Not(HasSubstr("robot."))) << entry;
  }
}

}  // namespace
}  // namespace tumble::app
