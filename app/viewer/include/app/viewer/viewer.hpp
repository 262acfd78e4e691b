#pragma once
/// @file The viewer without its window: what input does (shortcuts, camera, dropped files), the
/// session it drives, recording and screenshots, and the messages shown to the user. The SDL
/// window feeds it events and frame times and shows its frames; tests drive it directly.

#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/video/robot_picture.hpp"
#include "app/viewer/viewer_camera.hpp"
#include "app/viewer/viewer_input.hpp"
#include "app/viewer/viewer_session.hpp"
#include "base/image.hpp"
#include "render/draw_list.hpp"
#include "render/renderer.hpp"

namespace tumble::media {
class ImageSink;
}  // namespace tumble::media

namespace tumble::app::viewer {

/// Frames per second of recorded videos (frames are taken on the wall clock, so a recording
/// plays at the speed it was seen).
inline constexpr double kRecordFps = 30.0;

/// A line shown in the window for a while (errors stay until dismissed).
struct Notice {
  std::string text;
  bool error = false;
  double since = 0.0;  ///< viewer clock (s) when it was posted
};

class Viewer {
 public:
  /// Seconds an information notice stays up.
  static constexpr double kNoticeSeconds = 6.0;

  /// Draws with `renderer`; screenshots and recordings go to `output_dir` unless given a path.
  Viewer(render::Renderer& renderer, std::filesystem::path output_dir);
  ~Viewer();
  Viewer(const Viewer&) = delete;
  Viewer& operator=(const Viewer&) = delete;

  Session& session() { return session_; }
  const Session& session() const { return session_; }
  OrbitCamera& camera() { return camera_; }

  /// Opens a scene or a mesh (with the integrator and dt of `choice` where given), or a robot
  /// file (is_robot_file: URDF, SDF, MJCF), shown still with its links' inertials; on failure
  /// posts the error and keeps what was open. Returns whether it opened.
  bool open(const std::filesystem::path& file, const RunChoice& choice = {});
  /// How robot files are opened from now on (the command line's --from, --package-path).
  void set_robot_options(const RobotPictureOptions& options) { robot_options_ = options; }
  /// The robot file open now, or null (a scene or a mesh, or nothing, is open).
  const RobotPicture* robot() const { return robot_.get(); }
  /// The file open now (empty before the first open).
  const std::filesystem::path& file() const { return file_; }

  /// One input event. Shortcuts are ignored while ImGui takes the keyboard (typing in a field);
  /// the camera ignores presses while ImGui takes the mouse.
  void handle(const InputEvent& event, bool imgui_wants_keyboard, bool imgui_wants_mouse);
  /// What a shortcut does (also the panel buttons).
  void apply(Shortcut shortcut);

  /// The window is now `width` x `height` pixels: later frames are drawn at that size (the
  /// renderer's framebuffers, the camera's aspect, the overlay and its text follow). A recording
  /// in progress is finished first (a video keeps one frame size) and says so. On a failure
  /// (no framebuffer of that size) posts the error and keeps the old size; returns whether the
  /// frames now have the new size.
  bool resize(int width, int height);

  /// Real time passed since the last frame: the session steps, the camera follows, notices
  /// age, the recording takes frames.
  void update(double wall_seconds);
  /// The draw list of the current frame (the session's, seen by the user's camera).
  render::DrawList frame();
  /// Whether the next frame's scene image (before the panels) is needed: while recording.
  bool wants_scene_image() const;
  /// After a frame is drawn: `scene` is the frame without the panels (what a render writes),
  /// captured when wants_scene_image() said so before the frame, else null; `window` is what
  /// the window shows (for screenshots). A recording takes frames only from scene images, so a
  /// recording started by a panel button during the frame begins with the next one.
  void frame_drawn(const Image* scene, const Image& window);

  // --- Recording and screenshots ---------------------------------------------------------------
  bool recording() const { return sink_ != nullptr; }
  /// Starts recording to `path` (dir/ for PNG frames, .mp4, .webm or .gif); empty: a new
  /// name in the output folder. Errors are posted.
  void start_recording(const std::filesystem::path& path = {});
  /// Finishes the video (posted with its frame count).
  void stop_recording();
  /// Abandons the recording in progress unfinished: its temporary output is removed and
  /// nothing is written under its name (an interrupted viewer). False when none was running.
  bool discard_recording();
  const std::filesystem::path& recording_path() const { return recording_path_; }
  /// Writes the next drawn window to `path` (PNG; empty: a new name in the output folder).
  void request_screenshot(const std::filesystem::path& path = {});

  // --- What the panels show and edit ------------------------------------------------------------
  bool help_shown = false;
  bool follow = false;  ///< camera target on `follow_body`'s centre of mass
  std::size_t follow_body = 0;
  std::size_t selected_body = 0;  ///< the inspector's and the initial-state editor's body
  /// The robot's link the inspector shows and the picture highlights: chosen in the list, or
  /// by clicking it in the view (a press and release within a few pixels).
  std::optional<std::size_t> selected_link;
  bool open_requested = false;  ///< Ctrl+O: the panel focuses its file field
  bool quit_requested() const { return quit_; }
  /// Back to the camera a render of the scene starts with.
  void reset_camera();

  void notify(const std::string& text, bool error = false);
  const std::vector<Notice>& notices() const { return notices_; }
  void dismiss_notice(std::size_t index);

 private:
  std::filesystem::path fresh_name(const std::string& extension) const;
  bool open_robot(const std::filesystem::path& file);
  /// A left click (press and release in place) on the view picks the robot's link under it.
  void pick(const MouseButtonEvent& button, bool imgui_wants_mouse);
  double reach() const;

  render::Renderer& renderer_;
  std::filesystem::path output_dir_;
  Session session_;
  OrbitCamera camera_;
  std::filesystem::path file_;
  std::vector<Notice> notices_;
  double clock_ = 0.0;
  bool quit_ = false;

  RobotPictureOptions robot_options_;
  std::unique_ptr<RobotPicture> robot_;
  std::unique_ptr<RobotDrawing> robot_drawing_;  ///< after the session's meshes, if any
  std::optional<Eigen::Vector2f> press_;         ///< where the left button went down

  std::unique_ptr<media::ImageSink> sink_;
  std::filesystem::path recording_path_;
  double recorded_seconds_ = 0.0;  ///< wall time since the recording started
  std::size_t recorded_frames_ = 0;
  std::vector<std::filesystem::path> screenshots_;  ///< pending, written after the next frame
};

}  // namespace tumble::app::viewer
