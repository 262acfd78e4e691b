// `tumble render`: scene in, video or PNG frames out.
//
// Order of work, so that mistakes cost nothing: options and scene are checked, then the output
// is opened (an unwritable directory, an unknown extension or a missing ffmpeg fail before any
// mesh is read), then meshes are imported and frames rendered. The sinks write to a temporary
// name and rename on finish(); every failure or interruption destroys the sink unfinished,
// which removes the temporary, so nothing half-written is ever left under the output name.
#include "app/render_command.hpp"

#include <signal.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <ostream>
#include <stdexcept>
#include <string_view>
#include <tuple>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/frame_builder.hpp"
#include "app/printf_number.hpp"
#include "app/simulate_command.hpp"
#include "engine/input_error.hpp"
#include "engine/integrators.hpp"
#include "engine/simulation.hpp"
#include "progress_bar.hpp"
#include "render/image_sink.hpp"
#include "render/renderer.hpp"

namespace tumble::app {
namespace {

using engine::InputError;

constexpr double kMaxFrames = 1e8;



/// Digits only (no sign, no spaces), at most 12 of them.
std::optional<std::size_t> whole_number(std::string_view text) {
  if (text.empty() || text.size() > 12) return std::nullopt;
  std::size_t value = 0;
  for (const char c : text) {
    if (c < '0' || c > '9') return std::nullopt;
    value = value * 10 + static_cast<std::size_t>(c - '0');
  }
  return value;
}

/// Applies --integrator and --dt to the scene and checks them.
void apply_simulation_options(const RenderOptions& options, SceneDescription& scene) {
  if (options.integrator) override_integrator(scene, *options.integrator);
  if (options.dt) {
    scene.dt = positive_option(*options.dt, "--dt");
    if (auto problem = step_problem(scene.dt, scene.duration)) {
      throw InputError("--dt: " + *problem);
    }
  }
}

/// The scene's render settings with the command-line options on top.
RenderSettings render_settings(const RenderOptions& options, const SceneDescription& scene) {
  std::vector<std::string> body_names;
  for (const BodyDescription& body : scene.bodies) body_names.push_back(body.name);
  RenderSettings settings = parse_render_settings(
      scene.render ? *scene.render : nlohmann::json::object(), scene.file.string(), body_names);
  if (options.size) std::tie(settings.width, settings.height) = parse_frame_size(*options.size);
  if (options.fps) {
    settings.fps = positive_option(*options.fps, "--fps");
    if (settings.fps > kMaxFps) {
      throw InputError("--fps: expected at most " + printf_number(kMaxFps) +
                       " frames per second, got " + printf_number(settings.fps));
    }
  }
  if (options.time_scale) settings.time_scale = positive_option(*options.time_scale, "--time-scale");
  if (options.antialiasing) {
    if (*options.antialiasing < 1 || *options.antialiasing > kMaxAntialiasing) {
      throw InputError("--aa: expected samples per pixel from 1 to " +
                       std::to_string(kMaxAntialiasing) + ", got " +
                       std::to_string(*options.antialiasing));
    }
    settings.antialiasing = *options.antialiasing;
  }
  if (options.no_overlay) settings.show.overlay = false;
  return settings;
}


// SIGINT and SIGTERM set a flag that the frame loop polls: the loop stops, the sink is
// destroyed unfinished (its temporary removed) and the command returns kExitInterrupted.
volatile std::sig_atomic_t interrupt_signal = 0;

void on_interrupt(int signal) {
  interrupt_signal = signal;
}

int report_interrupted(const InterruptGuard& guard, const RenderOptions& options,
                       std::ostream& err) {
  err << "tumble render: interrupted by " << guard.signal_name() << "; nothing written to '"
      << options.output.string() << "'\n";
  return kExitInterrupted;
}

/// Renders the plan into its output; returns the exit status. Throws on errors.
int render_scene(const RenderOptions& options, const InterruptGuard& guard, std::ostream& out,
                 std::ostream& err, bool progress) {
  const auto start = std::chrono::steady_clock::now();

  // Options and scene, then the output: both fail before any mesh is read.
  const RenderPlan plan = plan_render(options);
  std::unique_ptr<render::ImageSink> sink = open_render_output(options, plan.settings, plan.frames.first);

  // Meshes, simulation, renderer.
  RenderJob job(plan);
  const engine::Simulation& simulation = job.simulation();

  // Every frame time from 0 is visited (cheap: step and observe); frames in the range are
  // drawn and written.
  const FrameRange range = plan.frames;
  ProgressBar bar(err, range.end - range.first, "frames", progress);
  render::Image image;
  for (std::size_t frame = 0; frame < range.end; ++frame) {
    if (guard.interrupted()) break;
    job.advance_to(frame);
    if (frame < range.first) continue;
    job.draw(image);
    sink->write(image);
    bar.update(frame + 1 - range.first);
  }
  bar.clear();
  if (guard.interrupted()) {
    sink.reset();  // removes the temporary
    return report_interrupted(guard, options, err);
  }
  sink->finish();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  // A blow-up still gives a whole video (the last good state held), with a warning and status 3.
  int status = 0;
  if (simulation.blow_up()) {
    err << "tumble render: warning: blow-up: " << describe_blow_up(simulation)
        << "; later frames hold the last good state (t = " << printf_number(simulation.time(), "%.9g")
        << " s)\n";
    status = kExitBlowUp;
  }
  if (!options.quiet) {
    const std::size_t frames = sink->frames();
    out << "tumble render: " << frames << (frames == 1 ? " frame" : " frames") << " written to '"
        << options.output.string() << "' in " << printf_number(seconds, "%.2f") << " s ("
        << printf_number(seconds > 0.0 ? static_cast<double>(frames) / seconds : 0.0, "%.1f")
        << " frames/s)\n";
  }
  return status;
}

}  // namespace

InterruptGuard::InterruptGuard() {
  interrupt_signal = 0;
  install(SIGINT, old_interrupt_, interrupt_installed_);
  install(SIGTERM, old_terminate_, terminate_installed_);
}

InterruptGuard::~InterruptGuard() {
  if (interrupt_installed_) sigaction(SIGINT, &old_interrupt_, nullptr);
  if (terminate_installed_) sigaction(SIGTERM, &old_terminate_, nullptr);
}

bool InterruptGuard::interrupted() const {
  return interrupt_signal != 0;
}

const char* InterruptGuard::signal_name() const {
  return interrupt_signal == SIGTERM ? "SIGTERM" : "SIGINT";
}

void InterruptGuard::install(int signal, struct sigaction& old, bool& installed) {
  if (sigaction(signal, nullptr, &old) != 0 || old.sa_handler == SIG_IGN) return;
  struct sigaction action {};
  action.sa_handler = on_interrupt;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART | SA_RESETHAND;
  installed = sigaction(signal, &action, nullptr) == 0;
}

// H.264 and VP9 in yuv420p need even sides; that is checked here so the message says what to
// change rather than quoting the encoder.
std::unique_ptr<render::ImageSink> open_render_output(const VideoOptions& options,
                                                      const RenderSettings& settings,
                                                      std::size_t first_frame) {
  render::SinkKind kind{};
  try {
    kind = render::sink_kind(options.output);
  } catch (const std::invalid_argument& error) {
    throw InputError(error.what());
  }
  if ((kind == render::SinkKind::kMp4 || kind == render::SinkKind::kWebm) &&
      (settings.width % 2 != 0 || settings.height % 2 != 0)) {
    throw InputError("cannot write '" + options.output.string() +
                     "': " + (kind == render::SinkKind::kMp4 ? "H.264" : "VP9") +
                     " video needs an even width and height, got " +
                     std::to_string(settings.width) + "x" + std::to_string(settings.height) +
                     (options.size ? " (--size)" : " (the scene's render settings)"));
  }
  render::SinkOptions sink;
  sink.width = settings.width;
  sink.height = settings.height;
  sink.fps = settings.fps;
  sink.first_index = first_frame;
  return render::open_image_sink(options.output, sink);
}

CLI::App& add_render_command(CLI::App& cli, RenderOptions& options) {
  CLI::App& render = *cli.add_subcommand(
      "render", "Render a scene off-screen to a video (.mp4, .webm, .gif) or PNG frames (DIR/)");
  render.footer(
      "Frame k shows the simulation at t = k * time_scale / fps; the simulation keeps its own "
      "dt and a frame shows the last step at or before that time (the overlay prints the time "
      "shown). Frames: floor(duration * fps / time_scale) + 1. Settings also come from the "
      "scene's \"render\" object; options given here win. Outputs are written atomically. Exit "
      "status: 0 done, 1 bad scene/option/output or ffmpeg failure, 3 the run blew up (the "
      "output is still written, holding the last good state), 130 interrupted (nothing "
      "written).");
  add_video_options(
      render, options,
      "Image size WxH in pixels, e.g. 1280x720 (default 1280x720; even for .mp4/.webm)");
  render
      .add_option_function<std::string>(
          "--integrator", [&](const std::string& value) { options.integrator = value; },
          "Integrator NAME (overrides the scene; see tumble simulate --list-integrators)")
      ->type_name("NAME");
  render
      .add_option_function<double>(
          "--dt", [&](double value) { options.dt = value; }, "Simulation time step H in seconds")
      ->type_name("H");
  render
      .add_option_function<int>(
          "--aa", [&](int value) { options.antialiasing = value; },
          "Anti-aliasing samples per pixel N (1 off, 4 max on llvmpipe, about 3x slower)")
      ->type_name("N");
  render.add_flag("--no-overlay", options.no_overlay,
                  "No text or plots: title, integrator, time and drift plots are left out");
  return render;
}

void add_video_options(CLI::App& command, VideoOptions& options, const std::string& size_help) {
  command
      .add_option_function<std::string>(
          "SCENE", [&](const std::string& value) { options.scene = value; }, "Scene file (JSON)")
      ->required()
      ->type_name("FILE");
  command
      .add_option_function<std::string>(
          "-o,--output", [&](const std::string& value) { options.output = value; },
          "A .mp4 (H.264), .webm (VP9) or .gif file, or a directory ending in '/' for "
          "frame_000000.png, ...")
      ->required()
      ->type_name("OUTPUT");
  command
      .add_option_function<std::string>(
          "--size", [&](const std::string& value) { options.size = value; }, size_help)
      ->type_name("WxH");
  command
      .add_option_function<double>(
          "--fps", [&](double value) { options.fps = value; },
          "Video frames per second N (default 30)")
      ->type_name("N");
  command
      .add_option_function<std::string>(
          "--frames", [&](const std::string& value) { options.frames = value; },
          "Render only frames A:B, half-open (A to B-1, counted from 0; A: and :B allowed); they "
          "equal the same frames of a full render, and PNG files keep their frame numbers")
      ->type_name("A:B");
  command
      .add_option_function<double>(
          "--time-scale", [&](double value) { options.time_scale = value; },
          "Simulated seconds per second of video S (default 1; 0.5 is slow motion)")
      ->type_name("S");
  command.add_flag("-q,--quiet", options.quiet,
                   "No progress bar and no summary line (warnings and errors still print)");
}

std::size_t frame_count(double duration, double fps, double time_scale) {
  const double intervals = duration * fps / time_scale;
  return static_cast<std::size_t>(std::floor(intervals + 1e-9 * std::max(1.0, intervals))) + 1;
}

double frame_time(std::size_t frame, double fps, double time_scale) {
  return static_cast<double>(frame) * time_scale / fps;
}

std::pair<int, int> parse_frame_size(const std::string& text) {
  const std::size_t x = text.find_first_of("xX");
  const auto width = x == std::string::npos ? std::nullopt : whole_number(text.substr(0, x));
  const auto height = x == std::string::npos ? std::nullopt : whole_number(text.substr(x + 1));
  const auto fits = [](std::optional<std::size_t> side) {
    return side && *side >= 1 && *side <= static_cast<std::size_t>(kMaxImageSide);
  };
  if (!fits(width) || !fits(height)) {
    throw InputError("--size: expected WIDTHxHEIGHT in pixels, each from 1 to " +
                     std::to_string(kMaxImageSide) + " (e.g. 1280x720), got \"" + text + "\"");
  }
  return {static_cast<int>(*width), static_cast<int>(*height)};
}

FrameRange parse_frame_range(const std::string& text, std::size_t total) {
  const std::size_t colon = text.find(':');
  const std::string expected =
      "--frames: expected A:B, the frames A to B-1 with 0 <= A < B <= " + std::to_string(total) +
      " (the scene has " + std::to_string(total) + " frames), got \"" + text + "\"";
  if (colon == std::string::npos) throw InputError(expected);
  const std::string first = text.substr(0, colon);
  const std::string end = text.substr(colon + 1);
  const auto a = first.empty() ? std::optional<std::size_t>(0) : whole_number(first);
  const auto b = end.empty() ? std::optional<std::size_t>(total) : whole_number(end);
  if (!a || !b || !(*a < *b) || *b > total) throw InputError(expected);
  return {*a, *b};
}

RenderPlan plan_render(const RenderOptions& options) {
  RenderPlan plan;
  plan.scene = load_scene(options.scene);
  apply_simulation_options(options, plan.scene);
  plan.settings = render_settings(options, plan.scene);
  const double frames = plan.scene.duration * plan.settings.fps / plan.settings.time_scale;
  if (!(frames < kMaxFrames)) {
    throw InputError(plan.scene.file.string() + ": a duration of " +
                     printf_number(plan.scene.duration) + " s at " + printf_number(plan.settings.fps) +
                     " fps and time scale " + printf_number(plan.settings.time_scale) +
                     " makes more than " + printf_number(kMaxFrames) + " frames");
  }
  plan.total_frames = frame_count(plan.scene.duration, plan.settings.fps, plan.settings.time_scale);
  plan.frames = options.frames ? parse_frame_range(*options.frames, plan.total_frames)
                               : FrameRange{0, plan.total_frames};
  return plan;
}

struct RenderJob::Impl {
  // Declaration order is construction order: the builder holds the scene and the renderer.
  SceneDescription scene;
  RenderSettings settings;
  CompiledScene compiled;
  std::optional<engine::Simulation> simulation;
  std::unique_ptr<render::Renderer> own_renderer;  ///< empty when drawing with a shared one
  render::Renderer& renderer;
  FrameBuilder builder;
  std::size_t observed = 0;  ///< frame times observed so far

  Impl(const RenderPlan& plan, CompiledScene compiled_scene, render::Renderer* shared)
      : scene(plan.scene),
        settings(plan.settings),
        compiled(std::move(compiled_scene)),
        simulation(make_simulation(scene, compiled)),
        own_renderer(shared != nullptr
                         ? nullptr
                         : std::make_unique<render::Renderer>(render::RendererOptions{
                               settings.width, settings.height, settings.antialiasing})),
        renderer(shared != nullptr ? *shared : *own_renderer),
        builder(scene, compiled, settings, renderer) {}

  static engine::Simulation make_simulation(const SceneDescription& scene,
                                            const CompiledScene& compiled) {
    try {
      return engine::Simulation(compiled.bodies, compiled.initial, compiled.settings);
    } catch (const InputError& error) {  // e.g. the exact integrator on a body with torques
      throw InputError(scene.file.string() + ": " + error.what());
    }
  }

  /// Steps while the next step ends at or before `time` (within rounding of dt).
  void step_to(double time) {
    engine::Simulation& sim = *simulation;
    const double dt = sim.settings().dt;
    while (!sim.finished()) {
      const std::size_t next = sim.steps() + 1;
      const double next_time =
          next == sim.total_steps() ? sim.settings().duration : static_cast<double>(next) * dt;
      if (next_time > time + 1e-9 * dt) break;
      sim.step();  // false on a blow-up, after which finished() holds
    }
  }
};

RenderJob::RenderJob(const RenderPlan& plan)
    : impl_(std::make_unique<Impl>(plan, compile_scene(plan.scene, /*keep_geometry=*/true),
                                   nullptr)) {}

RenderJob::RenderJob(const RenderPlan& plan, render::Renderer& renderer)
    : impl_(std::make_unique<Impl>(plan, compile_scene(plan.scene, /*keep_geometry=*/true),
                                   &renderer)) {}

RenderJob::RenderJob(const RenderPlan& plan, const CompiledScene& compiled,
                     render::Renderer& renderer)
    : impl_(std::make_unique<Impl>(plan, [&] {
        CompiledScene copy = compiled;
        copy.settings = simulation_settings(plan.scene);
        return copy;
      }(), &renderer)) {}

RenderJob::~RenderJob() = default;

void RenderJob::advance_to(std::size_t frame) {
  if (frame + 1 < impl_->observed) {
    throw std::logic_error("RenderJob::advance_to: frames must not go back");
  }
  while (impl_->observed <= frame) {
    impl_->step_to(frame_time(impl_->observed, impl_->settings.fps, impl_->settings.time_scale));
    impl_->builder.observe(*impl_->simulation);
    ++impl_->observed;
  }
}

void RenderJob::draw(render::Image& image) {
  impl_->renderer.render(build(), image);
}

render::DrawList RenderJob::build() const {
  return impl_->builder.build(*impl_->simulation);
}

const engine::Simulation& RenderJob::simulation() const {
  return *impl_->simulation;
}

int run_render(const RenderOptions& options, std::ostream& out, std::ostream& err) {
  const bool progress = !options.quiet && ProgressBar::on_terminal(err);
  const InterruptGuard guard;
  // Input, output, ffmpeg and GL errors are one line and status 1, or an interruption when
  // one is under way (ffmpeg shares the terminal's SIGINT and may fail first).
  const auto fail = [&](const std::exception& error) {
    if (guard.interrupted()) return report_interrupted(guard, options, err);
    err << "tumble render: error: " << error.what() << "\n";
    return kExitInputError;
  };
  try {
    return render_scene(options, guard, out, err, progress);
  } catch (const std::runtime_error& error) {  // engine::InputError included
    return fail(error);
  } catch (const std::invalid_argument& error) {
    return fail(error);
  }
}

}  // namespace tumble::app
