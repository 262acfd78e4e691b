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
#include <SDL.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/video/render_job.hpp"
#include "app/viewer/view_options.hpp"
#include "app/viewer/viewer.hpp"
#include "app/viewer/viewer_input.hpp"
#include "app/viewer/viewer_panels.hpp"
#include "engine/input_error.hpp"
#include "render/imgui_layer.hpp"
#include "render/renderer.hpp"

namespace tumble::app {
namespace {

using viewer::InputEvent;
using viewer::Key;

/// SDL's key code as the viewer's Key.
Key key_from_sdl(SDL_Keycode code) {
  if (code >= SDLK_a && code <= SDLK_z) {
    return static_cast<Key>(static_cast<int>(Key::kA) + static_cast<int>(code - SDLK_a));
  }
  if (code >= SDLK_0 && code <= SDLK_9) {
    return static_cast<Key>(static_cast<int>(Key::k0) + static_cast<int>(code - SDLK_0));
  }
  switch (code) {
    case SDLK_SPACE:
      return Key::kSpace;
    case SDLK_RETURN:
      return Key::kEnter;
    case SDLK_KP_ENTER:
      return Key::kEnter;
    case SDLK_ESCAPE:
      return Key::kEscape;
    case SDLK_TAB:
      return Key::kTab;
    case SDLK_BACKSPACE:
      return Key::kBackspace;
    case SDLK_DELETE:
      return Key::kDelete;
    case SDLK_INSERT:
      return Key::kInsert;
    case SDLK_LEFT:
      return Key::kLeft;
    case SDLK_RIGHT:
      return Key::kRight;
    case SDLK_UP:
      return Key::kUp;
    case SDLK_DOWN:
      return Key::kDown;
    case SDLK_HOME:
      return Key::kHome;
    case SDLK_END:
      return Key::kEnd;
    case SDLK_PAGEUP:
      return Key::kPageUp;
    case SDLK_PAGEDOWN:
      return Key::kPageDown;
    case SDLK_MINUS:
      return Key::kMinus;
    case SDLK_KP_MINUS:
      return Key::kMinus;
    case SDLK_EQUALS:
      return Key::kEquals;
    case SDLK_PLUS:
      return Key::kEquals;
    case SDLK_KP_PLUS:
      return Key::kEquals;
    case SDLK_F1:
      return Key::kF1;
    default:
      return Key::kUnknown;
  }
}

/// One SDL event as the viewer's input, if it is one.
std::optional<InputEvent> translate(const SDL_Event& event) {
  switch (event.type) {
    case SDL_QUIT:
      return viewer::QuitEvent{};
    case SDL_KEYDOWN:
    case SDL_KEYUP: {
      viewer::KeyEvent key;
      key.key = key_from_sdl(event.key.keysym.sym);
      key.down = event.type == SDL_KEYDOWN;
      const Uint16 mod = event.key.keysym.mod;
      key.modifiers = {(mod & KMOD_CTRL) != 0, (mod & KMOD_SHIFT) != 0, (mod & KMOD_ALT) != 0};
      return key;
    }
    case SDL_TEXTINPUT:
      return viewer::TextEvent{event.text.text};
    case SDL_MOUSEMOTION:
      return viewer::MouseMoveEvent{static_cast<float>(event.motion.x),
                                    static_cast<float>(event.motion.y)};
    case SDL_MOUSEBUTTONDOWN:
    case SDL_MOUSEBUTTONUP: {
      int button = -1;
      if (event.button.button == SDL_BUTTON_LEFT) button = 0;
      if (event.button.button == SDL_BUTTON_RIGHT) button = 1;
      if (event.button.button == SDL_BUTTON_MIDDLE) button = 2;
      if (button < 0) return std::nullopt;
      return viewer::MouseButtonEvent{button, event.type == SDL_MOUSEBUTTONDOWN,
                                      static_cast<float>(event.button.x),
                                      static_cast<float>(event.button.y)};
    }
    case SDL_MOUSEWHEEL: {
      float dy = static_cast<float>(event.wheel.y);
      if (event.wheel.direction == SDL_MOUSEWHEEL_FLIPPED) dy = -dy;
      return viewer::WheelEvent{dy};
    }
    default:
      return std::nullopt;
  }
}

/// SDL's window, software renderer and streaming texture, released in reverse order.
struct Window {
  SDL_Window* window = nullptr;
  SDL_Renderer* renderer = nullptr;
  SDL_Texture* texture = nullptr;
  ~Window() {
    if (texture != nullptr) SDL_DestroyTexture(texture);
    if (renderer != nullptr) SDL_DestroyRenderer(renderer);
    if (window != nullptr) SDL_DestroyWindow(window);
    SDL_Quit();
  }
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

}  // namespace

bool viewer_available() {
  return true;
}

int run_viewer_window(const ViewOptions& options, std::ostream& out, std::ostream& err) {
  // Options first: nothing opens for a mistake.
  std::pair<int, int> size{1280, 720};
  std::vector<viewer::ScriptStep> script;
  try {
    if (options.size) size = parse_frame_size(*options.size);
    if (options.script) script = viewer::load_script(*options.script);
    if (options.dt) positive_option(*options.dt, "--dt");
    if (options.time_scale) positive_option(*options.time_scale, "--time-scale");
    if (options.exit_after) positive_option(*options.exit_after, "--exit-after");
    if (options.integrator) {
      SceneDescription unused;
      override_integrator(unused, *options.integrator);  // checks the name
    }
    std::error_code error;
    if (!std::filesystem::is_directory(options.output_dir, error)) {
      throw engine::InputError("--output-dir: '" + options.output_dir.string() +
                               "' is not a directory");
    }
  } catch (const engine::InputError& error) {
    err << "tumble view: " << error.what() << "\n";
    return 1;
  }
  const char* display = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  if ((display == nullptr || *display == '\0') && (wayland == nullptr || *wayland == '\0')) {
    err << "tumble view: no display (DISPLAY is not set); run it in a desktop session or under "
           "xvfb-run\n";
    return 1;
  }

  // The window.
  SDL_SetHint(SDL_HINT_FRAMEBUFFER_ACCELERATION, "0");
  SDL_SetHint(SDL_HINT_RENDER_DRIVER, "software");
  if (SDL_Init(SDL_INIT_VIDEO) != 0) {
    err << "tumble view: cannot open a window: " << SDL_GetError() << "\n";
    return 1;
  }
  Window window;
  const auto [width, height] = size;
  window.window = SDL_CreateWindow("tumble view", SDL_WINDOWPOS_CENTERED, SDL_WINDOWPOS_CENTERED,
                                   width, height, SDL_WINDOW_SHOWN);
  if (window.window != nullptr) {
    window.renderer = SDL_CreateRenderer(window.window, -1, SDL_RENDERER_SOFTWARE);
  }
  if (window.renderer != nullptr) {
    // RGBA bytes in memory, as the renderer hands them back.
    window.texture = SDL_CreateTexture(window.renderer, SDL_PIXELFORMAT_ABGR8888,
                                       SDL_TEXTUREACCESS_STREAMING, width, height);
  }
  if (window.texture == nullptr) {
    err << "tumble view: cannot open a window: " << SDL_GetError() << "\n";
    return 1;
  }
  SDL_EventState(SDL_DROPFILE, SDL_ENABLE);
  SDL_StartTextInput();

  // Renderer, ImGui layer, viewer.
  render::Renderer renderer({width, height, 1});
  render::ImGuiLayer layer(renderer);
  ImGui::SetCurrentContext(layer.context());
  viewer::configure_imgui_keys(ImGui::GetIO());
  viewer::ImGuiInput imgui_input;
  viewer::Viewer viewer(renderer, options.output_dir);
  viewer::Panels panels;
  viewer::ScriptPlayer player(std::move(script));

  const std::optional<std::filesystem::path> file =
      options.file ? options.file : default_view_scene();
  if (file) {
    viewer.open(*file, {options.integrator, options.dt});
  } else {
    viewer.notify("no scene given and the demo was not found: open a file", true);
  }
  if (options.time_scale) viewer.session().set_time_scale(*options.time_scale);
  viewer.session().set_paused(options.paused);

  // The frame loop.
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  Clock::time_point last = start;
  FrameClock frame_clock;
  render::Image window_image;
  render::Image scene_image;
  double played_wall = 0.0;  // wall time while playing, and simulated time it covered
  double played_simulated = 0.0;
  for (;;) {
    const Clock::time_point now = Clock::now();
    const double wall = std::chrono::duration<double>(now - last).count();
    const double since_start = std::chrono::duration<double>(now - start).count();
    last = now;

    // Input: the window's events, then the script's steps that are due.
    std::vector<InputEvent> events;
    SDL_Event event;
    while (SDL_PollEvent(&event) != 0) {
      if (event.type == SDL_DROPFILE) {
        events.push_back(viewer::DropEvent{event.drop.file});
        SDL_free(event.drop.file);
      } else if (auto input = translate(event)) {
        events.push_back(*input);
      }
    }
    for (viewer::ScriptStep& step : player.due(since_start)) {
      if (auto* input = std::get_if<InputEvent>(&step.action)) {
        events.push_back(std::move(*input));
      } else {
        viewer.request_screenshot(std::get<viewer::ScreenshotRequest>(step.action).path);
      }
    }
    ImGuiIO& io = ImGui::GetIO();
    for (const InputEvent& input : events) {
      imgui_input.feed(io, input);
      viewer.handle(input, io.WantCaptureKeyboard, io.WantCaptureMouse);
    }
    // A quit still draws this frame, so screenshots asked for with it are written.
    const bool last_frame =
        viewer.quit_requested() || (options.exit_after && since_start >= *options.exit_after);

    // Step, draw, show.
    const bool playing = !viewer.session().paused();
    const double simulated_before = viewer.session().time();
    viewer.update(wall);
    if (playing && viewer.session().time() >= simulated_before) {
      played_wall += wall;
      played_simulated += viewer.session().time() - simulated_before;
    }
    const viewer::FrameStats stats = frame_clock.stats();
    // The panels may start a recording while they are drawn: ask once, before the frame.
    const render::DrawList list = viewer.frame();
    render::Image* const scene = viewer.wants_scene_image() ? &scene_image : nullptr;
    const render::ExtraPass pass = layer.pass(
        static_cast<float>(wall), [&] { panels.draw(viewer, stats, width, height); },
        [&] { imgui_input.end_frame(ImGui::GetIO()); }, scene);
    renderer.render(list, window_image, pass);
    viewer.frame_drawn(scene, window_image);
    SDL_UpdateTexture(window.texture, nullptr, window_image.rgba.data(), 4 * width);
    SDL_RenderCopy(window.renderer, window.texture, nullptr, nullptr);
    SDL_RenderPresent(window.renderer);
    frame_clock.add(std::chrono::duration<double>(Clock::now() - now).count());
    if (last_frame) break;
  }
  if (viewer.recording()) viewer.stop_recording();

  if (options.stats) {
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    const auto [median, p95] = frame_clock.percentiles();
    out << "tumble view: " << frame_clock.count() << " frames in " << seconds << " s ("
        << static_cast<double>(frame_clock.count()) / seconds << " frames/s); frame time median "
        << median << " ms, 95th percentile " << p95 << " ms; real-time factor "
        << (played_wall > 0.0 ? played_simulated / played_wall : 0.0) << " at time scale "
        << viewer.session().time_scale() << "\n";
  }
  // Errors still shown when the window closed go to the terminal too.
  for (const viewer::Notice& notice : viewer.notices()) {
    if (notice.error) err << "tumble view: " << notice.text << "\n";
  }
  return 0;
}

}  // namespace tumble::app
