// `tumble render --lod on|off` and the scene's `render.lod`: a big mesh drawn from its
// simplified copies looks like the full mesh, and bad values are refused naming the option.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "app/scene/render_settings.hpp"
#include "media/png_io.hpp"
#include "support/command_test.hpp"
#include "support/image_compare.hpp"
#include "support/input_error.hpp"
#include "support/run_command.hpp"
#include "support/scene_builder.hpp"
#include "support/stl_writer.hpp"

namespace tumble::app {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;
using tumble::testing::run_command;
using tumble::testing::tumble_executable;

/// Binary STL of a torus about z (radii 0.6 and 0.25 m): 2 * rings * sides triangles.
std::string torus_stl(int rings, int sides) {
  const auto at = [&](int i, int j) {  // the same corner for i = rings as for 0: a closed mesh
    const double u = 2.0 * std::numbers::pi * (i % rings) / rings;
    const double v = 2.0 * std::numbers::pi * (j % sides) / sides;
    return Eigen::Vector3d((0.6 + 0.25 * std::cos(v)) * std::cos(u),
                           (0.6 + 0.25 * std::cos(v)) * std::sin(u), 0.25 * std::sin(v));
  };
  const auto count = static_cast<std::size_t>(2 * rings * sides);
  return testing::binary_stl_bytes(
      count,
      [&](std::size_t t) {
        const int quad = static_cast<int>(t / 2);
        const int i = quad / sides;
        const int j = quad % sides;
        const Eigen::Vector3d a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1),
                              d = at(i, j + 1);
        return t % 2 == 0 ? testing::StlTriangle{Eigen::Vector3d::Zero(), a, b, c}
                          : testing::StlTriangle{Eigen::Vector3d::Zero(), a, c, d};
      },
      "torus");
}

class RenderLod : public testing::CommandTest {};

TEST_F(RenderLod, TheSimplifiedDrawingLooksLikeTheFullMesh) {
  testing::write_stl_file(path("torus.stl"), torus_stl(400, 250));  // 200,000 triangles
  json scene = testing::SceneBuilder()
                   .duration(0.2)
                   .dt(0.01)
                   .body(testing::BodyBuilder("torus")
                             .erase("inertia")
                             .set("mesh", "torus.stl")
                             .erase("mass")
                             .set("density", 1000.0)
                             .angular_velocity({0.5, 2.0, 0.3}))
                   .json();
  scene["render"] = {{"size", {640, 360}}, {"show", {{"overlay", false}}}};
  const std::string file = write_scene(scene);
  for (const std::string lod : {"on", "off"}) {
    const auto result = run_command(tumble_executable() + " render " + file +
                                    " -q --frames 3:4 -o " + path(lod + "/") + " --lod " + lod);
    ASSERT_EQ(result.status, 0) << result.err;
  }
  const tumble::Image on = media::read_png(path("on/frame_000003.png"));
  const tumble::Image off = media::read_png(path("off/frame_000003.png"));
  ASSERT_EQ(on.width, 640);
  // Under a pixel of outline error: differing pixels are a thin fraction of the frame.
  EXPECT_LT(testing::pixels_differing(on, off, 24), on.width * on.height / 200);
  EXPECT_LT(testing::mean_difference(on, off), 0.5);
}

TEST_F(RenderLod, BadValuesNameTheOptionOrTheKey) {
  const std::string scene = write_scene(testing::tumbling_scene());
  const auto result =
      run_command(tumble_executable() + " render " + scene + " -o " + path("x.mp4") + " --lod yes");
  EXPECT_EQ(result.status, 1);
  EXPECT_THAT(result.err, HasSubstr("tumble render: error: --lod: expected on or off, got 'yes'"));
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;

  EXPECT_TRUE(parse_render_settings(json::object(), "s.json", {}).lod);
  EXPECT_FALSE(parse_render_settings(json{{"lod", false}}, "s.json", {}).lod);
  const std::string message = testing::input_error_of(
      [] {
        parse_render_settings(json{{"lod", "off"}}, "s.json", {});
      },
      "lod: \"off\"");
  EXPECT_THAT(message, HasSubstr("s.json: render.lod: expected"));
}

}  // namespace
}  // namespace tumble::app
