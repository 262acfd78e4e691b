// Tests of `tumble render`: frame timing against the simulation, and the executable end to end
// (videos checked with ffprobe/ffmpeg, PNG frames byte for byte, errors by their message).
#include "app/commands/render_command.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "base/errors.hpp"
#include "engine/simulation/simulation.hpp"
#include "media/png_io.hpp"
#include "render/renderer.hpp"
#include "support/command_test.hpp"
#include "support/image_compare.hpp"
#include "support/input_error.hpp"
#include "support/run_command.hpp"
#include "support/scene_builder.hpp"

namespace tumble::app {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;
using ::testing::Not;
using tumble::testing::fresh_directory;
using tumble::testing::mean_difference;
using tumble::testing::pixels_differing;
using tumble::testing::read_text;
using tumble::testing::run_command;
using tumble::testing::tumble_executable;

using testing::tumbling_scene;

std::string png_name(std::size_t index) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%06zu.png", index);
  return name;
}

class RenderCommand : public testing::CommandTest {
 protected:
  static testing::CommandResult render(const std::string& arguments) {
    return run_command(tumble_executable() + " render " + arguments);
  }

  /// Names in the test folder (temporaries start with '.').
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(dir_)) {
      names.push_back(entry.path().filename().string());
    }
    std::sort(names.begin(), names.end());
    return names;
  }

  /// Names that look like a sink's temporary.
  std::vector<std::string> leftovers() const {
    std::vector<std::string> names;
    for (const std::string& name : entries()) {
      if (name.find(".tmp") != std::string::npos) names.push_back(name);
    }
    return names;
  }
};

TEST_F(RenderCommand, HelpListsEveryOption) {
  const auto help = render("--help");
  EXPECT_EQ(help.status, 0);
  for (const char* option :
       {"SCENE", "-o,--output", "--size", "--fps", "--frames", "half-open", "--time-scale",
        "--integrator", "--dt", "--aa", "--no-overlay", "--quiet"}) {
    EXPECT_THAT(help.out, HasSubstr(option));
  }
  const auto top = run_command(tumble_executable() + " --help");
  EXPECT_THAT(top.out, HasSubstr("render"));
}

TEST_F(RenderCommand, Mp4HasTheSizeAndFrameCountAndMatchesThePngFrames) {
  // 0.5 s at 20 fps: 11 frames. Without the overlay, whose small text H.264 blurs, so the
  // comparison below sees the body.
  const std::string scene = write_scene(tumbling_scene());
  const auto video =
      render(scene + " -o " + path("out.mp4") + " --size 160x96 --fps 20 --no-overlay");
  ASSERT_EQ(video.status, 0) << video.err;
  EXPECT_EQ(video.err, "");  // not a terminal: no progress bar
  EXPECT_THAT(video.out, HasSubstr("tumble render: 11 frames written to '" + path("out.mp4")));
  EXPECT_THAT(video.out, HasSubstr(" frames/s)"));
  EXPECT_EQ(testing::probe_video(path("out.mp4")), "h264,160,96,11");

  const auto frames =
      render(scene + " -o " + path("frames/") + " --size 160x96 --fps 20 --no-overlay -q");
  ASSERT_EQ(frames.status, 0) << frames.err;
  EXPECT_EQ(frames.out, "");  // --quiet: no summary
  for (std::size_t k = 0; k < 11; ++k) {
    EXPECT_TRUE(std::filesystem::exists(dir_ / "frames" / png_name(k))) << k;
  }
  EXPECT_FALSE(std::filesystem::exists(dir_ / "frames" / png_name(11)));

  // Frame 6 decoded from the video matches PNG frame 6 (within the encoder's loss) far better
  // than its neighbours, which show the body turned.
  const auto decoded = run_command("ffmpeg -v error -i '" + path("out.mp4") +
                                   "' -vf 'select=eq(n\\,6)' -vframes 1 '" + path("six.png") + "'");
  ASSERT_EQ(decoded.status, 0) << decoded.err;
  const tumble::Image six = media::read_png(path("six.png"));
  const tumble::Image png[3] = {media::read_png(dir_ / "frames" / png_name(5)),
                                media::read_png(dir_ / "frames" / png_name(6)),
                                media::read_png(dir_ / "frames" / png_name(7))};
  EXPECT_LT(mean_difference(six, png[1]), 2.5);
  const std::size_t same = pixels_differing(six, png[1], 48);
  const std::size_t before = pixels_differing(six, png[0], 48);
  const std::size_t after = pixels_differing(six, png[2], 48);
  EXPECT_LT(same, 160u * 96u / 100u);  // measured: 46 of 15360, body edges (chroma halved)
  EXPECT_GT(before, 3 * same);         // measured: 256
  EXPECT_GT(after, 3 * same);          // measured: 233
  EXPECT_TRUE(leftovers().empty());
}

TEST_F(RenderCommand, TimeScaleAndFpsSetTheFrameCount) {
  // Slow motion at half speed doubles the frames; dt (0.03) need not divide the interval.
  const std::string scene = write_scene(tumbling_scene(0.5, 0.03));
  const auto slow = render(scene + " -o " + path("slow.gif") +
                           " --size 64x48 --fps 20 --time-scale 0.5 --no-overlay -q");
  ASSERT_EQ(slow.status, 0) << slow.err;
  EXPECT_EQ(testing::probe_video(path("slow.gif")), "gif,64,48,21");
}

TEST_F(RenderCommand, FrameRangeEqualsTheSameFramesOfAFullRender) {
  // The overlay's drift plots carry history, so the range must replay every frame time.
  const std::string scene = write_scene(tumbling_scene(0.4, 0.01));
  const auto full = render(scene + " -o " + path("full/") + " --size 160x96 --fps 20 -q");
  ASSERT_EQ(full.status, 0) << full.err;
  const auto part =
      render(scene + " -o " + path("part/") + " --size 160x96 --fps 20 --frames 4:7 -q");
  ASSERT_EQ(part.status, 0) << part.err;
  // A range's PNG files keep their frame numbers: part/frame_000004.png is frame 4.
  for (std::size_t k = 4; k < 7; ++k) {
    const std::string ranged = read_text(dir_ / "part" / png_name(k));
    ASSERT_FALSE(ranged.empty()) << "frame " << k;
    EXPECT_EQ(ranged, read_text(dir_ / "full" / png_name(k))) << "frame " << k;
  }
  EXPECT_FALSE(std::filesystem::exists(dir_ / "part" / png_name(3)));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "part" / png_name(7)));
  // The frames differ from each other (the body turns), so equality above means something.
  EXPECT_NE(read_text(dir_ / "full" / png_name(4)), read_text(dir_ / "full" / png_name(5)));

  // A range of a video has that many frames.
  const auto video =
      render(scene + " -o " + path("part.mp4") + " --size 160x96 --fps 20 --frames 2:5 -q");
  ASSERT_EQ(video.status, 0) << video.err;
  EXPECT_EQ(testing::probe_video(path("part.mp4")), "h264,160,96,3");
}

TEST_F(RenderCommand, AnOutputThatIsTheSceneThroughALinkIsRefusedAndTheSceneKept) {
  const std::string scene = write_scene(tumbling_scene());
  const std::string before = read_text(scene);
  std::filesystem::create_symlink(scene, path("video.mp4"));
  const auto result = render(scene + " -o " + path("video.mp4") + " --size 64x48 --fps 10");
  EXPECT_EQ(result.status, 1) << result.err;
  EXPECT_THAT(result.err, HasSubstr("tumble render: error: cannot write '" + path("video.mp4") +
                                    "': it is the input '" + scene + "'"));
  EXPECT_EQ(read_text(scene), before);
  EXPECT_TRUE(std::filesystem::is_symlink(path("video.mp4")));
}

TEST_F(RenderCommand, OutputErrorsLeaveNothingBehind) {
  const std::string scene = write_scene(tumbling_scene());
  const std::string options = " --size 64x48 --fps 10";

  const auto missing_directory = render(scene + " -o " + path("no/such/dir/out.mp4") + options);
  EXPECT_EQ(missing_directory.status, 1);
  EXPECT_THAT(missing_directory.err, HasSubstr("tumble render: error: cannot write '" +
                                               path("no/such/dir/out.mp4") + "'"));
  EXPECT_THAT(missing_directory.err, HasSubstr("does not exist"));

  const auto unknown = render(scene + " -o " + path("out.avi") + options);
  EXPECT_EQ(unknown.status, 1);
  EXPECT_THAT(unknown.err, HasSubstr("unknown output '" + path("out.avi") + "'"));

  const auto odd = render(scene + " -o " + path("out.mp4") + " --size 65x48");
  EXPECT_EQ(odd.status, 1);
  EXPECT_THAT(odd.err, HasSubstr("H.264 video needs an even width and height, got 65x48"));

  const auto no_ffmpeg = run_command("env PATH=/nonexistent " + tumble_executable() + " render " +
                                     scene + " -o " + path("out.mp4") + options);
  EXPECT_EQ(no_ffmpeg.status, 1);
  EXPECT_THAT(no_ffmpeg.err, HasSubstr("ffmpeg not found on PATH"));
  EXPECT_THAT(no_ffmpeg.err, HasSubstr(path("out.mp4")));

  // An ffmpeg that fails: its exit status and stderr are in the message.
  std::filesystem::create_directory(dir_ / "bin");
  std::ofstream(dir_ / "bin" / "ffmpeg") << "#!/bin/sh\necho 'fake ffmpeg: out of cheese' >&2\n"
                                            "exit 7\n";
  std::filesystem::permissions(dir_ / "bin" / "ffmpeg", std::filesystem::perms::owner_all);
  const auto failing =
      run_command("env PATH=" + path("bin") + ":/usr/bin:/bin " + tumble_executable() + " render " +
                  scene + " -o " + path("out.mp4") + options);
  EXPECT_EQ(failing.status, 1);
  EXPECT_THAT(failing.err, HasSubstr("ffmpeg failed writing '" + path("out.mp4") +
                                     "' (exit status 7): fake ffmpeg: out of cheese"));
  EXPECT_EQ(std::count(failing.err.begin(), failing.err.end(), '\n'), 1) << failing.err;

  // Nothing under any final name, no temporary.
  EXPECT_EQ(entries(), (std::vector<std::string>{"bin", "scene.json"}));
}

TEST_F(RenderCommand, OptionErrorsNameTheOption) {
  const std::string scene = write_scene(tumbling_scene());
  const std::string output = " -o " + path("out.mp4");  // 0.5 s at 30 fps: 16 frames
  const struct {
    std::string arguments;
    std::string message;
  } cases[] = {
      {"--frames 3:3",
       "--frames: expected A:B, the frames A to B-1 with 0 <= A < B <= 16 (the "
       "scene has 16 frames), got \"3:3\""},
      {"--frames 0:17", "got \"0:17\""},
      {"--frames 5", "got \"5\""},
      {"--size 160", "--size: expected WIDTHxHEIGHT in pixels, each from 1 to 8192"},
      {"--size 0x96", "got \"0x96\""},
      {"--fps 0", "--fps: expected a positive finite number, got 0"},
      {"--fps 241", "--fps: expected at most 240 frames per second, got 241"},
      {"--time-scale -1", "--time-scale: expected a positive finite number, got -1"},
      {"--aa 0",
       "--aa: expected off, fxaa or multisampling samples per pixel from 2 to 16 (1: off), got "
       "0"},
      {"--aa 17", "--aa: expected off, fxaa or multisampling samples per pixel"},
      {"--aa smaa", "got smaa"},
      {"--aa 4x", "got 4x"},
      {"--integrator nope", "--integrator: unknown integrator \"nope\"; expected one of: "},
      {"--dt 1", "--dt: expected a step no longer than the duration"},
  };
  for (const auto& c : cases) {
    const auto result = render(scene + output + " " + c.arguments);
    EXPECT_EQ(result.status, 1) << c.arguments;
    EXPECT_THAT(result.err, HasSubstr("tumble render: error: "));
    EXPECT_THAT(result.err, HasSubstr(c.message)) << c.arguments;
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  }
  EXPECT_TRUE(entries() == std::vector<std::string>{"scene.json"});
}

TEST_F(RenderCommand, SceneErrorsPassThroughWithFileAndJsonPath) {
  json bad_body = tumbling_scene();
  bad_body["bodies"][0]["mass"] = -2.0;
  const std::string file = write_scene(bad_body, "bad_body.json");
  const auto body = render(file + " -o " + path("out.mp4"));
  EXPECT_EQ(body.status, 1);
  EXPECT_THAT(body.err, HasSubstr("tumble render: error: " + file + ": bodies[0].mass"));

  json bad_render = tumbling_scene();
  bad_render["render"] = {{"fps", "fast"}};
  const std::string render_file = write_scene(bad_render, "bad_render.json");
  const auto settings = render(render_file + " -o " + path("out.mp4"));
  EXPECT_EQ(settings.status, 1);
  EXPECT_THAT(settings.err, HasSubstr("tumble render: error: " + render_file + ": render.fps"));

  const auto missing = render(path("nope.json") + " -o " + path("out.mp4"));
  EXPECT_EQ(missing.status, 1);
  EXPECT_THAT(missing.err, HasSubstr(path("nope.json")));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "out.mp4"));
  EXPECT_TRUE(leftovers().empty());
}

TEST_F(RenderCommand, SceneRenderSettingsApplyAndOptionsWin) {
  json scene = tumbling_scene(0.5, 0.01);
  scene["render"] = {{"size", {96, 64}}, {"fps", 10}};
  const std::string file = write_scene(scene);
  const auto from_scene = render(file + " -o " + path("scene.mp4") + " -q");
  ASSERT_EQ(from_scene.status, 0) << from_scene.err;
  EXPECT_EQ(testing::probe_video(path("scene.mp4")), "h264,96,64,6");
  const auto overridden = render(file + " -o " + path("options.mp4") + " -q --size 64x48 --fps 20");
  ASSERT_EQ(overridden.status, 0) << overridden.err;
  EXPECT_EQ(testing::probe_video(path("options.mp4")), "h264,64,48,11");
}

TEST_F(RenderCommand, NoOverlayLeavesTheTextOut) {
  // The same frame with and without the overlay differs; without it, the top-left corner
  // (where the panel sits) is plain background: every row there has a single colour.
  const std::string scene = write_scene(tumbling_scene(0.2, 0.01));
  const auto with = render(scene + " -o " + path("with/") + " --size 320x192 --fps 10 -q");
  const auto without =
      render(scene + " -o " + path("without/") + " --size 320x192 --fps 10 --no-overlay -q");
  ASSERT_EQ(with.status, 0) << with.err;
  ASSERT_EQ(without.status, 0) << without.err;
  const tumble::Image a = media::read_png(dir_ / "with" / png_name(1));
  const tumble::Image b = media::read_png(dir_ / "without" / png_name(1));
  EXPECT_GT(mean_difference(a, b), 1.0);
  for (int y = 0; y < 40; ++y) {
    for (int x = 1; x < 100; ++x) {
      ASSERT_TRUE(std::equal(b.pixel(x, y), b.pixel(x, y) + 3, b.pixel(0, y)))
          << "pixel " << x << "," << y;
    }
  }
}

TEST_F(RenderCommand, BlowUpWarnsFinishesTheVideoAndExitsWithThree) {
  // 3 s at 10 fps: 31 frames; the run blows up at t = 2.41 s, frames 25..30 hold t = 2.4 s.
  json needle = testing::fast_needle_scene();
  needle["integrator"] = "explicit-euler";
  const std::string scene = write_scene(needle);
  const auto result = render(scene + " -o " + path("out.mp4") + " --size 64x48 --fps 10");
  EXPECT_EQ(result.status, 3);
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  EXPECT_THAT(result.err, HasSubstr("tumble render: warning: blow-up: body 'needle' at step 241 "
                                    "(t = 2.41 s): "));
  EXPECT_THAT(result.err, HasSubstr("later frames hold the last good state (t = 2.4 s)"));
  EXPECT_THAT(result.out, HasSubstr("31 frames written"));
  EXPECT_EQ(testing::probe_video(path("out.mp4")), "h264,64,48,31");
  EXPECT_TRUE(leftovers().empty());

  // --integrator reaches the simulation: RK4 gets through the same run.
  const auto stable =
      render(scene + " -o " + path("rk4.mp4") + " --size 64x48 --fps 10 --integrator rk4 -q");
  EXPECT_EQ(stable.status, 0) << stable.err;
  EXPECT_EQ(stable.err, "");
}

TEST_F(RenderCommand, TerminationRemovesThePartialVideoAndExitsWith130) {
  // A long render, stopped with SIGTERM once frames are flowing into the temporary file.
  const std::string scene = write_scene(tumbling_scene(1000.0, 0.01));
  const std::string script = "(" + tumble_executable() + " render " + scene + " -o " +
                             path("long.mp4") +
                             " --size 64x48 --fps 30 & pid=$!; "
                             "for i in $(seq 200); do ls -a '" +
                             dir_.string() +
                             "' | grep -q '^\\.long\\.mp4\\.tmp' && break; sleep 0.02; done; "
                             "sleep 0.3; kill -TERM $pid; wait $pid)";
  const auto result = run_command(script);
  EXPECT_EQ(result.status, kExitInterrupted) << result.err;
  EXPECT_THAT(result.err, HasSubstr("tumble render: interrupted by SIGTERM; nothing written to '" +
                                    path("long.mp4") + "'"));
  EXPECT_EQ(result.out, "");
  EXPECT_EQ(entries(), std::vector<std::string>{"scene.json"});
}

TEST_F(RenderCommand, ProgressBarOnlyOnATerminal) {
  // `script` gives the command a pseudo-terminal; stdout and stderr both land in its output.
  const std::string scene = write_scene(tumbling_scene(0.5, 0.01));
  const std::string command =
      tumble_executable() + " render " + scene + " -o " + path("t.mp4") + " --size 64x48 --fps 10";
  const auto tty = run_command("script -qefc \"" + command + "\" /dev/null");
  ASSERT_EQ(tty.status, 0) << tty.out << tty.err;
  EXPECT_THAT(tty.out, HasSubstr("6/6 frames"));
  EXPECT_THAT(tty.out, HasSubstr(" frames/s"));
  EXPECT_THAT(tty.out, HasSubstr("\r"));
  const auto quiet = run_command("script -qefc \"" + command + " -q\" /dev/null");
  ASSERT_EQ(quiet.status, 0) << quiet.out << quiet.err;
  EXPECT_THAT(quiet.out, Not(HasSubstr("frames")));
}

TEST_F(RenderCommand, EveryDemoSceneRenders) {
  const std::filesystem::path scenes = std::filesystem::path(TUMBLE_SOURCE_DIR) / "assets/scenes";
  std::size_t count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(scenes)) {
    if (entry.path().extension() != ".json") continue;
    ++count;
    const std::string name = entry.path().stem().string();
    const auto result = render(entry.path().string() + " -o " + path(name + "/") +
                               " --size 160x96 --frames 0:3 -q");
    EXPECT_EQ(result.status, 0) << name << ": " << result.err;
    EXPECT_EQ(result.err, "") << name;
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_TRUE(std::filesystem::exists(dir_ / name / png_name(k))) << name << " " << k;
    }
  }
  EXPECT_GE(count, 6u);
}

}  // namespace
}  // namespace tumble::app
