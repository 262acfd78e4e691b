#include "app/viewer/viewer.hpp"

#include <unistd.h>

#include <algorithm>
#include <system_error>
#include <utility>

#include "base/errors.hpp"
#include "base/temporary_path.hpp"
#include "media/image_sink.hpp"
#include "media/png_io.hpp"
#include "render/overlay_layout.hpp"

namespace tumble::app::viewer {
namespace {

/// Writes `image` to `file` through a temporary sibling, so a failed write leaves nothing.
void write_png_atomically(const std::filesystem::path& file, const Image& image) {
  const std::filesystem::path temporary = temporary_sibling(file);
  try {
    media::write_png(temporary, image);
    std::filesystem::rename(temporary, file);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw;
  }
}

}  // namespace

Viewer::Viewer(render::Renderer& renderer, std::filesystem::path output_dir)
    : renderer_(renderer), output_dir_(std::move(output_dir)), session_(renderer) {}

Viewer::~Viewer() {
  if (sink_) stop_recording();
}

bool Viewer::open(const std::filesystem::path& file, const RunChoice& choice) {
  if (is_robot_file(file)) return open_robot(file);
  if (auto error = session_.open(file, choice)) {
    notify(*error, true);
    return false;
  }
  // The session's new meshes replaced the robot's (uploaded after the session's mark).
  robot_drawing_.reset();
  robot_.reset();
  selected_link.reset();
  file_ = file;
  selected_body = 0;
  follow_body = 0;
  reset_camera();
  notify("opened " + file.string());
  return true;
}

bool Viewer::open_robot(const std::filesystem::path& file) {
  // Everything that can fail first, so a failure keeps what was open.
  std::unique_ptr<RobotPicture> picture;
  try {
    picture = std::make_unique<RobotPicture>(load_robot_picture(file, robot_options_));
  } catch (const std::exception& error) {
    const std::string text = error.what();
    notify(text.rfind(file.string(), 0) == 0 ? text : file.string() + ": " + text, true);
    return false;
  }
  // The scene's meshes and an earlier robot's go (the robot's came after the session's mark).
  robot_drawing_.reset();
  session_.close();
  robot_ = std::move(picture);
  robot_drawing_ = std::make_unique<RobotDrawing>(*robot_, renderer_);
  file_ = file;
  selected_link.reset();
  press_.reset();
  reset_camera();
  notify("opened " + file.string() + ": " + std::to_string(robot_->links.size()) + " links, " +
         std::to_string(robot_->differing()) + " differing from their computed inertials");
  return true;
}

void Viewer::reset_camera() {
  if (robot_) {
    camera_ = OrbitCamera(robot_camera(*robot_, renderer_.width(), renderer_.height()));
    return;
  }
  if (session_.empty()) return;
  camera_ = OrbitCamera(session_.scene_camera());
}

double Viewer::reach() const {
  if (!robot_) return session_.reach();
  return robot_->bounds.isEmpty() ? 1.0 : 0.5 * robot_->bounds.diagonal().norm();
}

void Viewer::pick(const MouseButtonEvent& button, bool imgui_wants_mouse) {
  if (!robot_ || button.button != 0) return;
  if (button.down) {
    if (imgui_wants_mouse) return;
    press_ = Eigen::Vector2f(button.x, button.y);
    return;
  }
  // A drag orbits; only a release where the press was picks.
  constexpr float kClickSlopPx = 4.0f;
  const bool click =
      press_ && (*press_ - Eigen::Vector2f(button.x, button.y)).norm() <= kClickSlopPx;
  press_.reset();
  if (!click) return;
  selected_link = pick_link(*robot_, camera_.camera(reach()), renderer_.width(), renderer_.height(),
                            button.x, button.y);
}

void Viewer::handle(const InputEvent& event, bool imgui_wants_keyboard, bool imgui_wants_mouse) {
  if (std::holds_alternative<QuitEvent>(event)) {
    quit_ = true;
    return;
  }
  if (const auto* drop = std::get_if<DropEvent>(&event)) {
    open(drop->path);
    return;
  }
  if (const auto* key = std::get_if<KeyEvent>(&event)) {
    if (imgui_wants_keyboard || !key->down) return;
    if (auto shortcut = shortcut_for(*key, help_shown)) apply(*shortcut);
    return;
  }
  if (const auto* button = std::get_if<MouseButtonEvent>(&event)) pick(*button, imgui_wants_mouse);
  camera_.handle(event, imgui_wants_mouse);
}

void Viewer::apply(Shortcut shortcut) {
  switch (shortcut) {
    case Shortcut::kTogglePause:
      // At the end of the run, play means from the start again.
      if (session_.paused() && session_.finished()) session_.reset();
      session_.set_paused(!session_.paused());
      break;
    case Shortcut::kStep:
      session_.step();
      break;
    case Shortcut::kReset:
      session_.reset();
      break;
    case Shortcut::kSlower:
      session_.set_time_scale(session_.time_scale() / 2.0);
      break;
    case Shortcut::kFaster:
      session_.set_time_scale(session_.time_scale() * 2.0);
      break;
    case Shortcut::kToggleHelp:
      help_shown = !help_shown;
      break;
    case Shortcut::kScreenshot:
      request_screenshot();
      break;
    case Shortcut::kToggleRecord:
      if (recording()) {
        stop_recording();
      } else {
        start_recording();
      }
      break;
    case Shortcut::kOpen:
      open_requested = true;
      break;
    case Shortcut::kQuit:
      quit_ = true;
      break;
  }
}

bool Viewer::resize(int width, int height) {
  if (width == renderer_.width() && height == renderer_.height()) return true;
  if (recording()) {
    stop_recording();
    notify("recording stopped: the window was resized (a video keeps one frame size)");
  }
  try {
    renderer_.resize(width, height);
  } catch (const std::exception& error) {
    notify(std::string("resizing the window: ") + error.what(), true);
    return false;
  }
  session_.refit_frames();
  return true;
}

void Viewer::update(double wall_seconds) {
  wall_seconds = std::max(wall_seconds, 0.0);
  clock_ += wall_seconds;
  session_.advance(wall_seconds);
  if (follow && !session_.empty()) {
    const auto& states = session_.simulation().states();
    camera_.set_target(states[std::min(follow_body, states.size() - 1)].position);
  }
  if (sink_) recorded_seconds_ += wall_seconds;
  // Information fades; errors stay until dismissed.
  std::erase_if(notices_, [&](const Notice& notice) {
    return !notice.error && clock_ - notice.since > kNoticeSeconds;
  });
}

render::DrawList Viewer::frame() {
  if (robot_drawing_) {
    const float font_px =
        render::overlay_font_px(renderer_.width(), renderer_.height(), session_.font_scale());
    return robot_drawing_->frame(camera_.camera(reach()), selected_link, true, font_px);
  }
  return session_.frame(camera_.camera(session_.reach()));
}

bool Viewer::wants_scene_image() const {
  return sink_ != nullptr;
}

void Viewer::frame_drawn(const Image* scene, const Image& window) {
  // Screenshots: what the window shows.
  for (const std::filesystem::path& path : screenshots_) {
    try {
      write_png_atomically(path, window);
      notify("screenshot " + path.string());
    } catch (const std::exception& error) {
      notify("screenshot " + path.string() + ": " + error.what(), true);
    }
  }
  screenshots_.clear();

  // Recording: a frame each 1/kRecordFps of wall time, the latest drawn state repeated when
  // drawing is slower than that.
  if (!sink_ || scene == nullptr) return;
  try {
    while (static_cast<double>(recorded_frames_) <= recorded_seconds_ * kRecordFps) {
      sink_->write(*scene);
      ++recorded_frames_;
    }
  } catch (const std::exception& error) {
    sink_.reset();  // abandons the temporary output
    notify("recording " + recording_path_.string() + ": " + error.what(), true);
  }
}

void Viewer::start_recording(const std::filesystem::path& path) {
  if (sink_) return;
  recording_path_ = path.empty() ? fresh_name(".mp4") : path;
  media::SinkOptions options;
  options.width = renderer_.width();
  options.height = renderer_.height();
  options.fps = kRecordFps;
  try {
    sink_ = media::open_image_sink(recording_path_, options);
  } catch (const std::exception& error) {
    notify("recording " + recording_path_.string() + ": " + error.what(), true);
    return;
  }
  recorded_seconds_ = 0.0;
  recorded_frames_ = 0;
  notify("recording to " + recording_path_.string());
}

void Viewer::stop_recording() {
  if (!sink_) return;
  std::unique_ptr<media::ImageSink> sink = std::move(sink_);
  try {
    sink->finish();
    notify("recorded " + std::to_string(sink->frames()) + " frames to " + recording_path_.string());
  } catch (const std::exception& error) {
    notify("recording " + recording_path_.string() + ": " + error.what(), true);
  }
}

bool Viewer::discard_recording() {
  if (!sink_) return false;
  sink_.reset();  // an unfinished sink stops its encoder and removes its temporary output
  return true;
}

void Viewer::request_screenshot(const std::filesystem::path& path) {
  screenshots_.push_back(path.empty() ? fresh_name(".png") : path);
}

void Viewer::notify(const std::string& text, bool error) {
  notices_.push_back({text, error, clock_});
}

void Viewer::dismiss_notice(std::size_t index) {
  if (index < notices_.size()) notices_.erase(notices_.begin() + static_cast<long>(index));
}

std::filesystem::path Viewer::fresh_name(const std::string& extension) const {
  // "<scene>-<n><extension>" with the first n not taken (screenshots and videos counted apart).
  std::string stem = session_.empty() && !robot_ ? "tumble" : file_.stem().string();
  if (stem.empty()) stem = "tumble";
  for (int n = 1;; ++n) {
    std::filesystem::path candidate = output_dir_ / (stem + "-" + std::to_string(n) + extension);
    std::error_code error;
    const bool pending =
        std::find(screenshots_.begin(), screenshots_.end(), candidate) != screenshots_.end();
    if (!std::filesystem::exists(candidate, error) && !pending) return candidate;
  }
}

}  // namespace tumble::app::viewer
