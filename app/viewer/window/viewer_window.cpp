// `tumble view`'s window: SDL2 shows the off-screen renderer's frames, turns its events into the
// viewer's InputEvents and hands them, with a script's timed steps, to Dear ImGui and the
// Viewer.
//
// Design note
// - SDL draws with its software renderer into a streaming texture that receives each frame's
//   RGBA pixels; SDL's framebuffer acceleration is turned off first, because it would put a
//   GLX context next to OSMesa's and crash (SDL_HINT_FRAMEBUFFER_ACCELERATION "0", set
//   before SDL_Init).
// - ImGui gets input from our own event translation (viewer_input.hpp), not from the SDL
//   backend, which polls the pointer from the window system: scripted events then behave
//   exactly as real ones.
// - The simulation steps on the wall clock (Session::advance), so a slow frame shows less
//   often, not slower physics.
// - The window is resizable: each frame reads the renderer's output size, and a new size goes
//   to Viewer::resize (the off-screen framebuffers, hence the GL viewport and the camera's
//   aspect, and the overlay), the streaming texture and ImGui (display size, text and spacing
//   from render::overlay_font_px at the session's font scale). While the window is minimised
//   (or has no pixels) nothing is drawn; the simulation keeps its clock.
// - SIGINT and SIGTERM are caught by an InterruptGuard that the frame loop polls, not by SDL
//   (which would turn them into a quit, and a quit finishes a recording): an interrupted
//   viewer discards the recording in progress and exits with 130.
#include <SDL.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "app/support/interrupt_guard.hpp"
#include "app/video/render_job.hpp"
#include "app/viewer/view_options.hpp"
#include "app/viewer/viewer.hpp"
#include "app/viewer/viewer_input.hpp"
#include "app/viewer/viewer_panels.hpp"
#include "base/errors.hpp"
#include "render/imgui_layer.hpp"
#include "render/overlay_layout.hpp"
#include "render/renderer.hpp"
#include "sdl_input.hpp"

namespace tumble::app {
namespace {

using viewer::InputEvent;

/// The exit status of an interrupted command (app/support/exit_status.hpp).
constexpr int kExitInterrupted = 130;

/// SDL's video subsystem, for the software renderer; quit when it goes, if it started.
class SdlVideo {
 public:
  SdlVideo() = default;
  ~SdlVideo() {
    if (started_) SDL_Quit();
  }
  SdlVideo(const SdlVideo&) = delete;
  SdlVideo& operator=(const SdlVideo&) = delete;

  /// False when SDL cannot start (SDL_GetError says why).
  bool start() {
    SDL_SetHint(SDL_HINT_FRAMEBUFFER_ACCELERATION, "0");
    // SIGINT and SIGTERM are the InterruptGuard's, never a quit event.
    SDL_SetHint(SDL_HINT_NO_SIGNAL_HANDLERS, "1");
    SDL_SetHint(SDL_HINT_RENDER_DRIVER, "software");
    started_ = SDL_Init(SDL_INIT_VIDEO) == 0;
    return started_;
  }

 private:
  bool started_ = false;
};

struct SdlDestroy {
  void operator()(SDL_Window* window) const { SDL_DestroyWindow(window); }
  void operator()(SDL_Renderer* renderer) const { SDL_DestroyRenderer(renderer); }
  void operator()(SDL_Texture* texture) const { SDL_DestroyTexture(texture); }
};

/// SDL's window, software renderer and streaming texture, released in reverse order, then SDL.
class SdlWindow {
 public:
  static constexpr int kMinWidth = 320;
  static constexpr int kMinHeight = 180;

  /// Opens a resizable `width` x `height` window taking dropped files and text input; false
  /// when any part fails (SDL_GetError says why).
  bool open(int width, int height) {
    if (!video_.start()) return false;
    window_.reset(SDL_CreateWindow("tumble view", SDL_WINDOWPOS_CENTERED, SDL_WINDOWPOS_CENTERED,
                                   width, height, SDL_WINDOW_SHOWN | SDL_WINDOW_RESIZABLE));
    if (window_) renderer_.reset(SDL_CreateRenderer(window_.get(), -1, SDL_RENDERER_SOFTWARE));
    if (!renderer_ || !make_texture(width, height)) return false;
    // Smaller than this and the panel's text no longer fits (unless --size asked for less).
    SDL_SetWindowMinimumSize(window_.get(), std::min(width, kMinWidth),
                             std::min(height, kMinHeight));
    SDL_EventState(SDL_DROPFILE, SDL_ENABLE);
    SDL_StartTextInput();
    return true;
  }

  /// A `width` x `height` streaming texture for the frames (RGBA bytes in memory, as the
  /// renderer hands them back); false when SDL cannot make it.
  bool make_texture(int width, int height) {
    texture_.reset(SDL_CreateTexture(renderer_.get(), SDL_PIXELFORMAT_ABGR8888,
                                     SDL_TEXTUREACCESS_STREAMING, width, height));
    return texture_ != nullptr;
  }

  /// The pixels the window shows now, or nothing while it is minimised, hidden or empty.
  std::optional<std::pair<int, int>> drawable_size() const {
    if ((SDL_GetWindowFlags(window_.get()) & (SDL_WINDOW_MINIMIZED | SDL_WINDOW_HIDDEN)) != 0) {
      return std::nullopt;
    }
    int width = 0;
    int height = 0;
    if (SDL_GetRendererOutputSize(renderer_.get(), &width, &height) != 0) return std::nullopt;
    if (width <= 0 || height <= 0) return std::nullopt;
    return std::pair{width, height};
  }

  /// Asks the window system for a `width` x `height` window (a script's resize); the new size
  /// arrives like a user's resize.
  void request_size(int width, int height) { SDL_SetWindowSize(window_.get(), width, height); }

  /// Shows a frame, stretched over the window when their sizes differ.
  void show(const Image& image) {
    if (!texture_) return;
    SDL_UpdateTexture(texture_.get(), nullptr, image.rgba.data(), 4 * image.width);
    SDL_RenderCopy(renderer_.get(), texture_.get(), nullptr, nullptr);
    SDL_RenderPresent(renderer_.get());
  }

 private:
  SdlVideo video_;
  std::unique_ptr<SDL_Window, SdlDestroy> window_;
  std::unique_ptr<SDL_Renderer, SdlDestroy> renderer_;
  std::unique_ptr<SDL_Texture, SdlDestroy> texture_;
};

/// Frame times, for the panel and --stats.
class FrameClock {
 public:
  void add(double seconds) {
    all_.push_back(seconds);
    recent_.push_back(seconds);
    if (recent_.size() > 60) recent_.erase(recent_.begin());
  }
  viewer::FrameStats stats() const {
    viewer::FrameStats out;
    if (recent_.empty()) return out;
    double total = 0.0;
    for (double t : recent_) total += t;
    out.frame_ms = 1e3 * total / static_cast<double>(recent_.size());
    out.frames_per_second = out.frame_ms > 0.0 ? 1e3 / out.frame_ms : 0.0;
    return out;
  }
  /// Median and 95th percentile (ms), skipping the first frames (font atlas, first upload).
  std::pair<double, double> percentiles() const {
    std::vector<double> times(all_.begin() + std::min<std::ptrdiff_t>(10, all_.size()), all_.end());
    if (times.empty()) return {0.0, 0.0};
    std::sort(times.begin(), times.end());
    const auto at = [&](double q) {
      return 1e3 * times[static_cast<std::size_t>(q * static_cast<double>(times.size() - 1))];
    };
    return {at(0.5), at(0.95)};
  }
  std::size_t count() const { return all_.size(); }

 private:
  std::vector<double> all_;
  std::vector<double> recent_;
};

/// What the checked options give the window: its size and the script's steps.
struct WindowPlan {
  int width = 1280;
  int height = 720;
  std::vector<viewer::ScriptStep> script;
};

/// Checks every option before anything opens. Throws tumble::InputError.
WindowPlan checked_options(const ViewOptions& options) {
  WindowPlan plan;
  if (options.size) std::tie(plan.width, plan.height) = parse_frame_size(*options.size);
  if (options.script) plan.script = viewer::load_script(*options.script);
  if (options.dt) positive_option(*options.dt, "--dt");
  if (options.time_scale) positive_option(*options.time_scale, "--time-scale");
  if (options.font_scale) font_scale_option(*options.font_scale);
  if (options.exit_after) positive_option(*options.exit_after, "--exit-after");
  package_paths(options.package_paths);  // checks each NAME=DIR
  if (options.integrator) {
    SceneDescription unused;
    override_integrator(unused, *options.integrator);  // checks the name
  }
  std::error_code error;
  if (!std::filesystem::is_directory(options.output_dir, error)) {
    throw tumble::InputError("--output-dir: '" + options.output_dir.string() +
                             "' is not a directory");
  }
  return plan;
}

bool has_display() {
  const char* display = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  return !((display == nullptr || *display == '\0') && (wayland == nullptr || *wayland == '\0'));
}

using Clock = std::chrono::steady_clock;

double seconds_between(Clock::time_point from, Clock::time_point to) {
  return std::chrono::duration<double>(to - from).count();
}

/// The viewer in an open window: its renderer, ImGui layer, panels and script, the frame loop,
/// and what it measured.
class ViewerWindow {
 public:
  /// Sets up the renderer, ImGui and the viewer, and opens the scene the options name.
  ViewerWindow(const ViewOptions& options, SdlWindow& window, WindowPlan plan);
  /// Runs frames until a quit or --exit-after, then stops any recording; or until `guard`
  /// caught a signal, leaving a recording as it is. Returns false when interrupted.
  bool run(const InterruptGuard& guard);
  /// After an interrupted run: discards the recording in progress (nothing under its name)
  /// and says so in one line on `err`. Returns kExitInterrupted.
  int report_interrupted(const InterruptGuard& guard, std::ostream& err);
  /// --stats on `out`; the errors still shown on `err`.
  void report(std::ostream& out, std::ostream& err) const;

 private:
  /// Feeds the window's events, then the script's steps due, to ImGui and the viewer.
  void handle_input(double since_start);
  /// Follows the window's size (Viewer::resize, the texture); false while it shows nothing
  /// (minimised), when no frame is drawn.
  bool follow_window_size();
  /// Steps the simulation by `wall` seconds, draws the frame with the panels and shows it.
  void draw_frame(double wall);

  const ViewOptions& options_;
  SdlWindow& window_;
  int width_;  ///< of the frames drawn
  int height_;
  std::pair<int, int> refused_{0, 0};  ///< a window size the frames could not take
  render::Renderer renderer_;
  render::ImGuiLayer layer_;
  viewer::ImGuiInput imgui_input_;
  viewer::Viewer viewer_;
  viewer::Panels panels_;
  viewer::ScriptPlayer player_;
  Clock::time_point start_;
  FrameClock frame_clock_;
  Image window_image_;
  Image scene_image_;
  double played_wall_ = 0.0;  // wall time while playing, and simulated time it covered
  double played_simulated_ = 0.0;
};

ViewerWindow::ViewerWindow(const ViewOptions& options, SdlWindow& window, WindowPlan plan)
    : options_(options),
      window_(window),
      width_(plan.width),
      height_(plan.height),
      renderer_({width_, height_, 1}),
      layer_(renderer_),
      viewer_(renderer_, options.output_dir),
      player_(std::move(plan.script)) {
  ImGui::SetCurrentContext(layer_.context());
  viewer::configure_imgui_keys(ImGui::GetIO());
  viewer_.session().set_font_scale(options.font_scale);
  const std::optional<std::filesystem::path> file =
      options.file ? options.file : default_view_scene();
  RobotPictureOptions robot_options;
  if (options.robot_from == "visual") robot_options.from = robot::GeometrySource::visual;
  robot_options.package_paths = options.package_paths;
  viewer_.set_robot_options(robot_options);
  if (file) {
    viewer_.open(*file, {options.integrator, options.dt, options.allow_overlap});
  } else {
    viewer_.notify("no scene given and the demo was not found: open a file", true);
  }
  if (options.time_scale) viewer_.session().set_time_scale(*options.time_scale);
  viewer_.session().set_paused(options.paused);
}

bool ViewerWindow::run(const InterruptGuard& guard) {
  start_ = Clock::now();
  Clock::time_point last = start_;
  std::size_t drawn = 0;  // frames drawn: the --frame-clock's ticks
  for (;;) {
    if (guard.interrupted()) return false;
    const Clock::time_point now = Clock::now();
    // The viewer's clock: the wall clock, or with --frame-clock the frames drawn so far (a
    // hidden or minimised window, drawing nothing, stops that clock).
    const double wall = !options_.frame_clock ? seconds_between(last, now)
                        : drawn == 0          ? 0.0
                                              : 1.0 / viewer::kRecordFps;
    const double since_start = options_.frame_clock
                                   ? static_cast<double>(drawn) / viewer::kRecordFps
                                   : seconds_between(start_, now);
    last = now;
    handle_input(since_start);
    // A quit still draws this frame, so screenshots asked for with it are written.
    const bool last_frame =
        viewer_.quit_requested() || (options_.exit_after && since_start >= *options_.exit_after);
    if (follow_window_size()) {
      draw_frame(wall);
      ++drawn;
      frame_clock_.add(seconds_between(now, Clock::now()));
    } else {
      // Minimised: the wall clock goes on (the frame clock does not), nothing is drawn.
      viewer_.update(options_.frame_clock ? 0.0 : wall);
      SDL_Delay(20);
    }
    if (last_frame) break;
  }
  if (guard.interrupted()) return false;  // came with the last frame: still not a quit
  if (viewer_.recording()) viewer_.stop_recording();
  return true;
}

int ViewerWindow::report_interrupted(const InterruptGuard& guard, std::ostream& err) {
  const std::filesystem::path recording = viewer_.recording_path();
  err << "tumble view: interrupted by " << guard.signal_name();
  if (viewer_.discard_recording()) {
    err << "; recording discarded, nothing written to '" << recording.string() << "'";
  }
  err << "\n";
  return kExitInterrupted;
}

void ViewerWindow::handle_input(double since_start) {
  std::vector<InputEvent> events = window_events();
  for (viewer::ScriptStep& step : player_.due(since_start)) {
    if (auto* input = std::get_if<InputEvent>(&step.action)) {
      events.push_back(std::move(*input));
    } else if (const auto* resize = std::get_if<viewer::ResizeRequest>(&step.action)) {
      window_.request_size(resize->width, resize->height);
    } else {
      viewer_.request_screenshot(std::get<viewer::ScreenshotRequest>(step.action).path);
    }
  }
  ImGuiIO& io = ImGui::GetIO();
  for (const InputEvent& input : events) {
    imgui_input_.feed(io, input);
    viewer_.handle(input, io.WantCaptureKeyboard, io.WantCaptureMouse);
  }
}

bool ViewerWindow::follow_window_size() {
  const std::optional<std::pair<int, int>> size = window_.drawable_size();
  if (!size) return false;
  const int width = std::min(size->first, kMaxImageSide);
  const int height = std::min(size->second, kMaxImageSide);
  if ((width == width_ && height == height_) || std::pair{width, height} == refused_) return true;
  // On a failure the frames keep their size, stretched over the window (the error is shown
  // once: that size is not tried again).
  if (!viewer_.resize(width, height)) {
    refused_ = {width, height};
  } else if (window_.make_texture(width, height)) {
    width_ = width;
    height_ = height;
  } else {
    viewer_.notify(std::string("resizing the window: ") + SDL_GetError(), true);
    refused_ = {width, height};
    viewer_.resize(width_, height_);
    window_.make_texture(width_, height_);
  }
  return true;
}

void ViewerWindow::draw_frame(double wall) {
  const bool playing = !viewer_.session().paused();
  const double simulated_before = viewer_.session().time();
  viewer_.update(wall);
  if (playing && viewer_.session().time() >= simulated_before) {
    played_wall_ += wall;
    played_simulated_ += viewer_.session().time() - simulated_before;
  }
  const viewer::FrameStats stats = frame_clock_.stats();
  // The panels may start a recording while they are drawn: ask once, before the frame.
  const render::DrawList list = viewer_.frame();
  Image* const scene = viewer_.wants_scene_image() ? &scene_image_ : nullptr;
  layer_.set_font_px(render::overlay_font_px(width_, height_, viewer_.session().font_scale()));
  const render::ExtraPass pass = layer_.pass(
      static_cast<float>(wall), [&] { panels_.draw(viewer_, stats, width_, height_); },
      [&] { imgui_input_.end_frame(ImGui::GetIO()); }, scene);
  renderer_.render(list, window_image_, pass);
  viewer_.frame_drawn(scene, window_image_);
  window_.show(window_image_);
}

void ViewerWindow::report(std::ostream& out, std::ostream& err) const {
  if (options_.stats) {
    const double seconds = seconds_between(start_, Clock::now());
    const auto [median, p95] = frame_clock_.percentiles();
    out << "tumble view: " << frame_clock_.count() << " frames in " << seconds << " s ("
        << static_cast<double>(frame_clock_.count()) / seconds << " frames/s); frame time median "
        << median << " ms, 95th percentile " << p95 << " ms; real-time factor "
        << (played_wall_ > 0.0 ? played_simulated_ / played_wall_ : 0.0) << " at time scale "
        << viewer_.session().time_scale() << "\n";
    // The layout of the last frame: what the window shows, its text and the control panel.
    out << "tumble view: window " << width_ << "x" << height_ << ", text " << layer_.font_px()
        << " px, control panel " << viewer::panel_rect(width_, height_, layer_.font_px()).width
        << " px wide\n";
  }
  // Errors still shown when the window closed go to the terminal too.
  for (const viewer::Notice& notice : viewer_.notices()) {
    if (notice.error) err << "tumble view: " << notice.text << "\n";
  }
}

}  // namespace

bool viewer_available() {
  return true;
}

int run_viewer_window(const ViewOptions& options, std::ostream& out, std::ostream& err) {
  // Options first: nothing opens for a mistake.
  WindowPlan plan;
  try {
    plan = checked_options(options);
  } catch (const tumble::InputError& error) {
    err << "tumble view: " << error.what() << "\n";
    return 1;
  }
  if (!has_display()) {
    err << "tumble view: no display (DISPLAY is not set); run it in a desktop session or under "
           "xvfb-run\n";
    return 1;
  }
  // Caught from before the window opens (SDL's default handlers are off as well).
  const InterruptGuard guard;
  SdlWindow window;
  if (!window.open(plan.width, plan.height)) {
    err << "tumble view: cannot open a window: " << SDL_GetError() << "\n";
    return 1;
  }
  ViewerWindow viewer_window(options, window, std::move(plan));
  if (!viewer_window.run(guard)) return viewer_window.report_interrupted(guard, err);
  viewer_window.report(out, err);
  return 0;
}

}  // namespace tumble::app
