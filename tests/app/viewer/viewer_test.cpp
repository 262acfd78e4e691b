#include "app/viewer/viewer.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "media/png_io.hpp"
#include "render/renderer.hpp"
#include "support/command_test.hpp"
#include "support/scene_builder.hpp"

namespace tumble::app::viewer {
namespace {

using ::testing::HasSubstr;
using tumble::testing::directory_entries;

/// A free brick drifting along +x at 0.5 m/s while it spins; dt = 5 ms.
nlohmann::json drifting_brick() {
  return testing::SceneBuilder()
      .duration(20.0)
      .dt(0.005)
      .body(
          testing::BodyBuilder("brick").velocity({0.5, 0.0, 0.0}).angular_velocity({0.1, 2.0, 0.1}))
      .json();
}

KeyEvent press(Key key, bool ctrl = false) {
  return KeyEvent{key, true, Modifiers{ctrl, false, false}};
}

/// An image of one colour, to tell the scene image from the window image.
tumble::Image solid(int width, int height, std::uint8_t grey) {
  tumble::Image image;
  image.width = width;
  image.height = height;
  image.rgba.assign(static_cast<std::size_t>(4 * width * height), grey);
  for (std::size_t i = 3; i < image.rgba.size(); i += 4) image.rgba[i] = 255;
  return image;
}

class ViewerApp : public testing::CommandTest {
 protected:
  static void SetUpTestSuite() {
    render::RendererOptions options;
    options.width = 320;
    options.height = 240;
    renderer_ = std::make_unique<render::Renderer>(options);
  }
  static void TearDownTestSuite() { renderer_.reset(); }

  void SetUp() override {
    CommandTest::SetUp();
    viewer_ = std::make_unique<Viewer>(*renderer_, dir_);
    scene_ = write_scene(drifting_brick());
    ASSERT_TRUE(viewer_->open(scene_));
  }
  void TearDown() override {
    viewer_.reset();
    CommandTest::TearDown();
  }

  /// Input as the window delivers it, ImGui wanting neither keyboard nor mouse.
  void key(Key k, bool ctrl = false) { viewer_->handle(press(k, ctrl), false, false); }

  /// One frame of the window loop: time passes, the frame is drawn and handed back.
  tumble::Image frame(double wall_seconds) {
    viewer_->update(wall_seconds);
    tumble::Image image = renderer_->render(viewer_->frame());
    viewer_->frame_drawn(&image, image);
    return image;
  }

  bool has_error(const std::string& text) const {
    for (const Notice& notice : viewer_->notices()) {
      if (notice.error && notice.text.find(text) != std::string::npos) return true;
    }
    return false;
  }

  static std::unique_ptr<render::Renderer> renderer_;
  std::unique_ptr<Viewer> viewer_;
  std::string scene_;
};
std::unique_ptr<render::Renderer> ViewerApp::renderer_;

TEST_F(ViewerApp, OpenStartsFromTheScenesCameraAndSaysSo) {
  EXPECT_EQ(viewer_->file(), scene_);
  ASSERT_FALSE(viewer_->notices().empty());
  EXPECT_EQ(viewer_->notices().back().text, "opened " + scene_);
  EXPECT_FALSE(viewer_->notices().back().error);
  const render::Camera start = viewer_->session().scene_camera();
  EXPECT_NEAR((viewer_->camera().target() - start.target.cast<double>()).norm(), 0.0, 1e-5);
  EXPECT_NEAR((viewer_->camera().eye() - start.eye.cast<double>()).norm(), 0.0,
              1e-4 * viewer_->camera().distance());
  // frame() is seen through the user's camera.
  viewer_->camera().orbit(40.0, 0.0);
  const render::DrawList list = viewer_->frame();
  EXPECT_NEAR((list.camera.eye.cast<double>() - viewer_->camera().eye()).norm(), 0.0,
              1e-5 * viewer_->camera().distance());
}

TEST_F(ViewerApp, KeysDoWhatTheShortcutsSay) {
  Session& session = viewer_->session();
  ASSERT_FALSE(session.paused());
  key(Key::kSpace);
  EXPECT_TRUE(session.paused());
  key(Key::kSpace);
  EXPECT_FALSE(session.paused());

  // Right: one dt, paused.
  key(Key::kRight);
  EXPECT_TRUE(session.paused());
  EXPECT_EQ(session.simulation().steps(), 1u);
  EXPECT_EQ(session.time(), 0.005);
  viewer_->update(0.5);
  EXPECT_EQ(session.time(), 0.005);

  // Backspace: back to t = 0.
  key(Key::kSpace);
  viewer_->update(0.2);
  ASSERT_GT(session.time(), 0.1);
  key(Key::kBackspace);
  EXPECT_EQ(session.time(), 0.0);
  EXPECT_EQ(session.simulation().states()[0].position, session.initial_state(0).position);

  // - halves, = doubles, within [1/64, 64].
  key(Key::kMinus);
  EXPECT_EQ(session.time_scale(), 0.5);
  key(Key::kEquals);
  key(Key::kEquals);
  EXPECT_EQ(session.time_scale(), 2.0);
  for (int i = 0; i < 10; ++i) key(Key::kEquals);
  EXPECT_EQ(session.time_scale(), 64.0);
  for (int i = 0; i < 20; ++i) key(Key::kMinus);
  EXPECT_EQ(session.time_scale(), 1.0 / 64.0);

  // F1 shows the help; Escape closes it first, then quits.
  key(Key::kF1);
  EXPECT_TRUE(viewer_->help_shown);
  key(Key::kEscape);
  EXPECT_FALSE(viewer_->help_shown);
  EXPECT_FALSE(viewer_->quit_requested());
  key(Key::kO, true);
  EXPECT_TRUE(viewer_->open_requested);
  key(Key::kEscape);
  EXPECT_TRUE(viewer_->quit_requested());
}

TEST_F(ViewerApp, SpaceAtTheEndPlaysFromTheStart) {
  std::ofstream(dir_ / "short.json") << R"({"duration": 0.1, "dt": 0.01, "bodies": [
      {"inertia": {"principal": [1, 2, 3]}, "mass": 1, "angular_velocity": [0, 1, 0]}]})";
  ASSERT_TRUE(viewer_->open(dir_ / "short.json"));
  viewer_->update(1.0);
  ASSERT_TRUE(viewer_->session().finished());
  ASSERT_TRUE(viewer_->session().paused());
  viewer_->handle(press(Key::kSpace), false, false);
  EXPECT_FALSE(viewer_->session().paused());
  EXPECT_EQ(viewer_->session().time(), 0.0);
  viewer_->update(0.05);
  EXPECT_NEAR(viewer_->session().time(), 0.05, 0.005 + 1e-12);
}

TEST_F(ViewerApp, KeysAreIgnoredWhileImGuiTakesTheKeyboard) {
  Session& session = viewer_->session();
  const std::vector<KeyEvent> keys = {
      press(Key::kSpace),   press(Key::kRight),  press(Key::kMinus),   press(Key::kEquals),
      press(Key::kF1),      press(Key::kEscape), press(Key::kP, true), press(Key::kR, true),
      press(Key::kO, true), press(Key::kQ, true)};
  viewer_->update(0.1);
  const double time = session.time();
  for (const KeyEvent& event : keys) viewer_->handle(event, true, false);
  EXPECT_FALSE(session.paused());
  EXPECT_EQ(session.time(), time);
  EXPECT_EQ(session.time_scale(), 1.0);
  EXPECT_FALSE(viewer_->help_shown);
  EXPECT_FALSE(viewer_->open_requested);
  EXPECT_FALSE(viewer_->quit_requested());
  EXPECT_FALSE(viewer_->recording());
  // Backspace too (it deletes a character in the field instead).
  viewer_->handle(press(Key::kBackspace), true, false);
  EXPECT_EQ(session.time(), time);
  // No screenshot was asked for: a drawn frame writes nothing.
  frame(0.0);
  EXPECT_EQ(directory_entries(dir_), std::vector<std::string>{"scene.json"});

  // Releases trigger nothing either.
  for (KeyEvent event : keys) {
    event.down = false;
    viewer_->handle(event, false, false);
  }
  EXPECT_FALSE(session.paused());
  EXPECT_FALSE(viewer_->quit_requested());
}

TEST_F(ViewerApp, QuitEventQuits) {
  viewer_->handle(QuitEvent{}, true, true);
  EXPECT_TRUE(viewer_->quit_requested());
}

TEST_F(ViewerApp, DroppedBadFilePostsAnErrorAndKeepsTheScene) {
  viewer_->update(0.3);
  const double time = viewer_->session().time();
  const std::string missing = path("nowhere.json");
  viewer_->handle(DropEvent{missing}, false, false);
  EXPECT_TRUE(has_error(missing));
  EXPECT_EQ(viewer_->file(), scene_);
  EXPECT_EQ(viewer_->session().scene().file, scene_);
  EXPECT_EQ(viewer_->session().time(), time);

  const std::string broken = path("broken.json");
  std::ofstream(broken) << "[1, 2";
  viewer_->handle(DropEvent{broken}, false, false);
  EXPECT_TRUE(has_error(broken));
  EXPECT_EQ(viewer_->file(), scene_);

  // Errors stay until dismissed.
  viewer_->update(2.0 * Viewer::kNoticeSeconds);
  EXPECT_TRUE(has_error(missing));
  const std::size_t count = viewer_->notices().size();
  viewer_->dismiss_notice(count - 1);
  EXPECT_EQ(viewer_->notices().size(), count - 1);
  EXPECT_FALSE(has_error(broken));
  viewer_->dismiss_notice(99);  // out of range: nothing
  EXPECT_EQ(viewer_->notices().size(), count - 1);

  // A good file dropped opens.
  const std::filesystem::path mesh =
      std::filesystem::path(TUMBLE_SOURCE_DIR) / "assets/meshes/coin.obj";
  viewer_->handle(DropEvent{mesh}, false, false);
  EXPECT_EQ(viewer_->file(), mesh);
  EXPECT_EQ(viewer_->session().compiled().bodies[0].name, "coin");
  EXPECT_EQ(viewer_->session().time(), 0.0);
}

TEST_F(ViewerApp, InformationNoticesFade) {
  viewer_->notify("hello");
  viewer_->update(Viewer::kNoticeSeconds - 0.5);
  ASSERT_FALSE(viewer_->notices().empty());
  EXPECT_EQ(viewer_->notices().back().text, "hello");
  viewer_->update(1.0);
  for (const Notice& notice : viewer_->notices()) EXPECT_NE(notice.text, "hello");
}

TEST_F(ViewerApp, CtrlPWritesTheWindowImageAfterTheNextFrame) {
  key(Key::kP, true);
  EXPECT_EQ(directory_entries(dir_), std::vector<std::string>{"scene.json"});  // not before a frame
  viewer_->update(0.1);
  const tumble::Image window = renderer_->render(viewer_->frame());
  const tumble::Image scene = solid(window.width, window.height, 10);
  viewer_->frame_drawn(&scene, window);

  const std::filesystem::path shot = dir_ / "scene-1.png";
  ASSERT_TRUE(std::filesystem::exists(shot));
  const tumble::Image written = media::read_png(shot);
  EXPECT_EQ(written.width, 320);
  EXPECT_EQ(written.height, 240);
  EXPECT_TRUE(written.rgba == window.rgba);
  EXPECT_EQ(viewer_->notices().back().text, "screenshot " + shot.string());

  // The next one takes the next name; two in one frame get two names.
  key(Key::kP, true);
  key(Key::kP, true);
  viewer_->frame_drawn(&scene, window);
  EXPECT_EQ(directory_entries(dir_),
            (std::vector<std::string>{"scene-1.png", "scene-2.png", "scene-3.png", "scene.json"}));
}

TEST_F(ViewerApp, ScreenshotToAnUnwritablePathPostsAnErrorAndLeavesNothing) {
  std::ofstream(dir_ / "plain") << "a file, not a folder\n";
  const std::filesystem::path target = dir_ / "plain" / "shot.png";
  viewer_->request_screenshot(target);
  frame(0.0);
  EXPECT_TRUE(has_error("screenshot " + target.string()));
  EXPECT_EQ(directory_entries(dir_), (std::vector<std::string>{"plain", "scene.json"}));
}

TEST_F(ViewerApp, RecordsAFrameEachThirtiethOfAWallSecond) {
  // PNG frames, so their count and content can be checked exactly.
  const std::filesystem::path frames = dir_ / "frames";
  viewer_->start_recording(frames.string() + "/");
  ASSERT_TRUE(viewer_->recording());
  EXPECT_TRUE(viewer_->wants_scene_image());
  const tumble::Image scene = solid(320, 240, 77);
  const tumble::Image window = solid(320, 240, 200);
  // Eight frames 1/8 s apart: 1 s of wall time. Rule (Viewer::frame_drawn): after wall time S
  // since the start, frames 0 .. floor(S x kRecordFps) have been written, so floor(30) + 1.
  for (int i = 0; i < 8; ++i) {
    viewer_->update(0.125);
    viewer_->frame_drawn(&scene, window);
  }
  viewer_->stop_recording();
  EXPECT_FALSE(viewer_->recording());
  EXPECT_FALSE(viewer_->wants_scene_image());
  EXPECT_EQ(viewer_->notices().back().text, "recorded 31 frames to " + frames.string() + "/");
  std::size_t count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(frames)) {
    (void)entry;
    ++count;
  }
  EXPECT_EQ(count, 31u);
  ASSERT_TRUE(std::filesystem::exists(frames / "frame_000030.png"));
  // Frames are the scene image (without the panels), not the window's.
  EXPECT_TRUE(media::read_png(frames / "frame_000030.png").rgba == scene.rgba);
  EXPECT_TRUE(media::read_png(frames / "frame_000000.png").rgba == scene.rgba);
}

TEST_F(ViewerApp, ARecordingStartedDuringAFrameBeginsWithTheNextSceneImage) {
  // The Record button is drawn with the panels, after the window loop decided whether to
  // capture the scene image: that frame has none, and none of the window's is recorded.
  const std::filesystem::path frames = dir_ / "frames";
  const tumble::Image scene = solid(320, 240, 77);
  const tumble::Image window = solid(320, 240, 200);
  viewer_->update(0.1);
  viewer_->start_recording(frames.string() + "/");
  viewer_->frame_drawn(nullptr, window);
  // The next frame has its scene image: it catches up on the wall time since the start.
  viewer_->update(0.1);
  viewer_->frame_drawn(&scene, window);
  viewer_->stop_recording();
  EXPECT_EQ(viewer_->notices().back().text, "recorded 4 frames to " + frames.string() + "/");
  for (const char* name : {"frame_000000.png", "frame_000003.png"}) {
    ASSERT_TRUE(std::filesystem::exists(frames / name)) << name;
    EXPECT_TRUE(media::read_png(frames / name).rgba == scene.rgba) << name;
  }
}

TEST_F(ViewerApp, CtrlRRecordsAVideoOfTheWallClock) {
  key(Key::kR, true);
  ASSERT_TRUE(viewer_->recording());
  const std::filesystem::path video = dir_ / "scene-1.mp4";
  EXPECT_EQ(viewer_->recording_path(), video);
  EXPECT_EQ(viewer_->notices().back().text, "recording to " + video.string());
  // 0.25 s x 5 frames = 1.25 s of wall time: floor(1.25 x 30) + 1 = 38 frames.
  for (int i = 0; i < 5; ++i) frame(0.25);
  EXPECT_FALSE(std::filesystem::exists(video));  // written atomically, at the end
  key(Key::kR, true);
  EXPECT_FALSE(viewer_->recording());
  EXPECT_EQ(viewer_->notices().back().text, "recorded 38 frames to " + video.string());
  ASSERT_TRUE(std::filesystem::exists(video));
  EXPECT_EQ(testing::probe_video(video.string()), "h264,320,240,38");
}

TEST_F(ViewerApp, RecordingToAnUnwritablePlacePostsAnErrorAndLeavesNothing) {
  std::ofstream(dir_ / "plain") << "a file, not a folder\n";
  const std::filesystem::path target = dir_ / "plain" / "clip.mp4";
  viewer_->start_recording(target);
  EXPECT_FALSE(viewer_->recording());
  EXPECT_TRUE(has_error("recording " + target.string()));
  frame(0.1);

  const std::filesystem::path unknown = dir_ / "clip.xyz";
  viewer_->start_recording(unknown);
  EXPECT_FALSE(viewer_->recording());
  EXPECT_TRUE(has_error("recording " + unknown.string()));
  frame(0.1);
  EXPECT_EQ(directory_entries(dir_), (std::vector<std::string>{"plain", "scene.json"}));
}

TEST_F(ViewerApp, FollowPutsTheTargetOnTheCentreOfMass) {
  const Eigen::Vector3d start_target = viewer_->camera().target();
  viewer_->update(0.4);
  EXPECT_EQ(viewer_->camera().target(), start_target);  // not following
  viewer_->follow = true;
  viewer_->update(0.4);
  const Eigen::Vector3d position = viewer_->session().simulation().states()[0].position;
  // Free drift at 0.5 m/s: x = 0.5 t.
  EXPECT_NEAR(position.x(), 0.5 * viewer_->session().time(), 1e-12);
  EXPECT_GT(position.x(), 0.15);
  EXPECT_EQ(viewer_->camera().target(), position);
}

TEST_F(ViewerApp, MouseDragOrbitsUnlessImGuiTakesTheMouse) {
  OrbitCamera& camera = viewer_->camera();
  const double azimuth = camera.azimuth_deg();
  const double elevation = camera.elevation_deg();
  // Over a panel: presses are not taken, so the drag does nothing.
  viewer_->handle(MouseButtonEvent{0, true, 100.0f, 100.0f}, false, true);
  viewer_->handle(MouseMoveEvent{150.0f, 110.0f}, false, true);
  viewer_->handle(MouseButtonEvent{0, false, 150.0f, 110.0f}, false, true);
  EXPECT_EQ(camera.azimuth_deg(), azimuth);
  EXPECT_EQ(camera.elevation_deg(), elevation);
  // On the scene: right drag turns the view right, down drag raises the eye.
  viewer_->handle(MouseButtonEvent{0, true, 100.0f, 100.0f}, false, false);
  viewer_->handle(MouseMoveEvent{150.0f, 110.0f}, false, false);
  viewer_->handle(MouseButtonEvent{0, false, 150.0f, 110.0f}, false, false);
  EXPECT_NEAR(camera.azimuth_deg(), azimuth - 50.0 * OrbitCamera::kDegreesPerPixel, 1e-9);
  EXPECT_NEAR(camera.elevation_deg(), elevation + 10.0 * OrbitCamera::kDegreesPerPixel, 1e-9);
  // Keyboard focus in ImGui does not stop the mouse.
  const double distance = camera.distance();
  viewer_->handle(WheelEvent{1.0f}, true, false);
  EXPECT_NEAR(camera.distance(), distance / OrbitCamera::kZoomPerNotch, 1e-12 * distance);
  // reset_camera goes back to the scene's.
  viewer_->reset_camera();
  EXPECT_NEAR(camera.azimuth_deg(), azimuth, 1e-9);
}

}  // namespace
}  // namespace tumble::app::viewer
