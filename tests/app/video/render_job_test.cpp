// A scene as a video (app/video): frame counts and times, the size and range options, the
// render job stepping and drawing frame by frame, and write_render (the whole `tumble render`)
// in process.
#include "app/video/render_job.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

#include <nlohmann/json.hpp>

#include "app/support/exit_status.hpp"
#include "engine/simulation/simulation.hpp"
#include "media/output_kind.hpp"
#include "media/png_io.hpp"
#include "render/renderer.hpp"
#include "support/command_test.hpp"
#include "support/image_compare.hpp"
#include "support/input_error.hpp"
#include "support/scene_builder.hpp"

namespace tumble::app {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;
using testing::tumbling_scene;

class RenderJobTest : public testing::CommandTest {};

TEST(RenderFrames, CountIsFloorOfDurationTimesFpsOverTimeScalePlusOne) {
  EXPECT_EQ(frame_count(20.0, 30.0, 1.0), 601u);
  EXPECT_EQ(frame_count(0.5, 30.0, 1.0), 16u);    // 15 intervals
  EXPECT_EQ(frame_count(0.55, 10.0, 1.0), 6u);    // 5.5 intervals: the last 0.05 s is not shown
  EXPECT_EQ(frame_count(0.5, 20.0, 0.5), 21u);    // slow motion: twice the frames
  EXPECT_EQ(frame_count(0.5, 20.0, 2.0), 6u);     // fast forward
  EXPECT_EQ(frame_count(0.29, 100.0, 1.0), 30u);  // 0.29 * 100 = 28.999999999999996 in doubles
  EXPECT_DOUBLE_EQ(frame_time(45, 30.0, 1.0), 1.5);
  EXPECT_DOUBLE_EQ(frame_time(45, 30.0, 0.5), 0.75);
}

TEST(RenderFrames, SizeAndRangeParsing) {
  EXPECT_EQ(parse_frame_size("1280x720"), std::make_pair(1280, 720));
  EXPECT_EQ(parse_frame_size("160X96"), std::make_pair(160, 96));
  for (const char* bad : {"", "x", "160", "160x", "x96", "0x96", "-160x96", "160x96x2", "1e3x96",
                          "99999x96", " 160x96"}) {
    const std::string message = testing::input_error_of([&] { parse_frame_size(bad); }, bad);
    EXPECT_THAT(message, HasSubstr("--size: expected WIDTHxHEIGHT"));
    EXPECT_THAT(message, HasSubstr("got \"" + std::string(bad) + "\""));
  }
  const FrameRange range = parse_frame_range("3:7", 10);
  EXPECT_EQ(range.first, 3u);
  EXPECT_EQ(range.end, 7u);
  EXPECT_EQ(parse_frame_range(":4", 10).first, 0u);
  EXPECT_EQ(parse_frame_range("4:", 10).end, 10u);
  EXPECT_EQ(parse_frame_range("9:10", 10).first, 9u);
  EXPECT_EQ(parse_frame_range(":", 10).end, 10u);
  for (const char* bad : {"3", "7:3", "3:3", "0:11", "a:b", "-1:3", "3:7:9"}) {
    EXPECT_THAT(testing::input_error_of([&] { parse_frame_range(bad, 10); }, bad),
                HasSubstr("--frames: expected A:B, the frames A to B-1 with 0 <= A < B <= 10"));
  }
}

TEST_F(RenderJobTest, FramesShowTheLastStepAtOrBeforeTheirTime) {
  // dt = 0.03 does not divide the frame interval 0.1 s: frame k shows step floor(k / 0.3).
  json scene = tumbling_scene(1.0, 0.03);
  RenderOptions options;
  options.scene = write_scene(scene);
  options.size = "64x48";
  options.fps = 10.0;
  const RenderPlan plan = plan_render(options);
  ASSERT_EQ(plan.total_frames, 11u);
  RenderJob job(plan);
  const std::size_t expected_steps[] = {0, 3, 6, 10, 13, 16, 20, 23, 26, 30, 34};
  for (std::size_t frame = 0; frame < plan.total_frames; ++frame) {
    job.advance_to(frame);
    EXPECT_EQ(job.simulation().steps(), expected_steps[frame]) << "frame " << frame;
    EXPECT_LE(job.simulation().time(), frame_time(frame, 10.0, 1.0) + 1e-12);
  }
  // The last step is the short one that ends exactly at the duration (34 steps).
  EXPECT_EQ(job.simulation().time(), 1.0);
  tumble::Image image;
  job.draw(image);
  EXPECT_EQ(image.width, 64);
  EXPECT_EQ(image.height, 48);
}

TEST_F(RenderJobTest, AJobFromASharedCompiledSceneIsTheJobOfItsOwnPlan) {
  // compare compiles a scene once for every integrator: a job made from that compiled scene and
  // another plan (another integrator and dt) must be the job that plan makes on its own.
  json scene = tumbling_scene(0.3, 0.01);
  scene["bodies"][0] = {{"name", "handle"},
                        {"mesh", std::string(TUMBLE_SOURCE_DIR) + "/assets/meshes/t_handle.obj"},
                        {"density", 1000.0},
                        {"angular_velocity", {0.3, 6.0, 0.3}}};
  RenderOptions options;
  options.scene = write_scene(scene);
  options.size = "64x48";
  options.fps = 10.0;
  const RenderPlan rk4 = plan_render(options);
  options.integrator = "splitting";
  options.dt = 0.004;
  const RenderPlan splitting = plan_render(options);

  const CompiledScene compiled = compile_scene(rk4.scene, /*keep_geometry=*/true);
  ASSERT_EQ(compiled.meshes_imported, 1u);
  render::Renderer renderer(render::RendererOptions{64, 48, 1});
  RenderJob shared(splitting, compiled, renderer);
  RenderJob own(splitting, renderer);
  EXPECT_EQ(shared.simulation().settings().integrator, engine::IntegratorKind::kSplitting);
  EXPECT_EQ(shared.simulation().settings().dt, 0.004);
  const std::size_t last = splitting.total_frames - 1;
  shared.advance_to(last);
  own.advance_to(last);
  EXPECT_EQ(shared.simulation().steps(), own.simulation().steps());
  const engine::BodyState& a = shared.simulation().states()[0];
  const engine::BodyState& b = own.simulation().states()[0];
  EXPECT_EQ(a.orientation.coeffs(), b.orientation.coeffs());
  EXPECT_EQ(a.angular_momentum, b.angular_momentum);
  tumble::Image from_shared, from_own;
  shared.draw(from_shared);
  own.draw(from_own);
  EXPECT_TRUE(from_shared.rgba == from_own.rgba);
}

TEST_F(RenderJobTest, WriteRenderWritesTheRangesFramesAsTheJobDrawsThem) {
  RenderOptions options;
  options.scene = write_scene(tumbling_scene(1.0, 0.03));
  options.size = "64x48";
  options.fps = 10.0;
  options.frames = "3:6";
  options.output = path("frames") + "/";
  std::ostringstream out, err;
  ASSERT_EQ(write_render(options, nullptr, out, err, /*progress=*/false), 0) << err.str();
  EXPECT_EQ(err.str(), "");
  EXPECT_THAT(out.str(), ::testing::StartsWith("tumble render: 3 frames written to '" +
                                               options.output.string() + "' in "));
  // Frames 3, 4 and 5 under their own numbers, each the image a job of the same plan draws.
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir_ / "frames")) {
    ++files;
  }
  EXPECT_EQ(files, 3u);
  const RenderPlan plan = plan_render(options);
  RenderJob job(plan);
  tumble::Image drawn;
  for (std::size_t frame = 3; frame < 6; ++frame) {
    job.advance_to(frame);
    job.draw(drawn);
    const tumble::Image written = media::read_png(dir_ / "frames" / media::frame_file_name(frame));
    EXPECT_EQ(testing::pixels_differing(written, drawn), 0u) << "frame " << frame;
  }
}

TEST_F(RenderJobTest, WriteRenderOfABlowUpWarnsAndWritesEveryFrame) {
  // As tests/app/commands/render_command_test.cpp: explicit Euler blows up at t = 2.41 s.
  json needle = testing::fast_needle_scene();
  needle["integrator"] = "explicit-euler";
  RenderOptions options;
  options.scene = write_scene(needle);
  options.size = "32x24";
  options.fps = 10.0;
  options.quiet = true;
  options.output = path("needle") + "/";
  std::ostringstream out, err;
  EXPECT_EQ(write_render(options, nullptr, out, err, false), kExitBlowUp);
  EXPECT_EQ(out.str(), "");
  const std::string warning = err.str();
  EXPECT_THAT(warning, ::testing::StartsWith("tumble render: warning: blow-up: body 'needle' at "
                                             "step 241 (t = 2.41 s): "));
  EXPECT_EQ(std::count(warning.begin(), warning.end(), '\n'), 1);
  EXPECT_THAT(warning, HasSubstr("; later frames hold the last good state (t = 2.4 s)\n"));
  EXPECT_TRUE(std::filesystem::exists(dir_ / "needle" / media::frame_file_name(30)));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "needle" / media::frame_file_name(31)));
}

TEST_F(RenderJobTest, WriteRenderInterruptedLeavesNothing) {
  RenderOptions options;
  options.scene = write_scene(tumbling_scene(1.0, 0.03));
  options.size = "32x24";
  options.output = path("cut") + "/";
  int asked = 0;
  std::ostringstream out, err;
  EXPECT_EQ(write_render(
                options, [&] { return ++asked > 4; }, out, err, false),
            kExitInterrupted);
  EXPECT_EQ(asked, 5);  // asked before each frame: four drawn, then stopped
  EXPECT_EQ(out.str(), "");
  EXPECT_FALSE(std::filesystem::exists(dir_ / "cut"));
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir_),
                          std::filesystem::directory_iterator()),
            1);  // the scene alone: no temporary left beside it
}

TEST_F(RenderJobTest, WriteRenderOfAnUnknownOutputKindIsAnInputErrorNamingIt) {
  RenderOptions options;
  options.scene = write_scene(tumbling_scene(1.0, 0.03));
  options.output = path("video.avi");
  std::ostringstream out, err;
  EXPECT_THAT(testing::input_error_of([&] { write_render(options, nullptr, out, err, false); }),
              HasSubstr("'" + options.output.string() + "'"));
  EXPECT_FALSE(std::filesystem::exists(options.output));
  EXPECT_EQ(out.str(), "");
}

}  // namespace
}  // namespace tumble::app
