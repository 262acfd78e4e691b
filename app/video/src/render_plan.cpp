// Planning a video of a scene: every option and the scene checked, the output opened, all
// before any mesh is read.
#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <tuple>
#include <vector>

#include "app/support/printf_number.hpp"
#include "app/video/render_job.hpp"
#include "base/errors.hpp"
#include "media/image_sink.hpp"

namespace tumble::app {
namespace {

using tumble::InputError;

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
  if (options.time_scale)
    settings.time_scale = positive_option(*options.time_scale, "--time-scale");
  if (options.font_scale) settings.font_scale = font_scale_option(*options.font_scale);
  if (options.antialiasing) {
    const std::optional<Antialiasing> parsed = antialiasing_from_text(*options.antialiasing);
    if (!parsed) {
      throw InputError(std::string("--aa: ") + kAntialiasingExpected + ", got " +
                       *options.antialiasing);
    }
    settings.antialiasing = *parsed;
  }
  if (options.lod) settings.lod = *options.lod;
  if (options.no_overlay) settings.show.overlay = false;
  return settings;
}

}  // namespace

// H.264 and VP9 in yuv420p need even sides; that is checked here so the message says what to
// change rather than quoting the encoder.
std::unique_ptr<media::ImageSink> open_render_output(
    const VideoOptions& options, const RenderSettings& settings, std::size_t first_frame,
    const std::vector<std::filesystem::path>& inputs, const std::string& part_manifest) {
  const media::SinkKind kind = media::sink_kind(options.output);  // InputError if unknown
  if ((kind == media::SinkKind::kMp4 || kind == media::SinkKind::kWebm) &&
      (settings.width % 2 != 0 || settings.height % 2 != 0)) {
    throw InputError("cannot write '" + options.output.string() +
                     "': " + (kind == media::SinkKind::kMp4 ? "H.264" : "VP9") +
                     " video needs an even width and height, got " +
                     std::to_string(settings.width) + "x" + std::to_string(settings.height) +
                     (options.size ? " (--size)" : " (the scene's render settings)"));
  }
  media::SinkOptions sink;
  sink.width = settings.width;
  sink.height = settings.height;
  sink.fps = settings.fps;
  sink.first_index = first_frame;
  sink.inputs = inputs;
  sink.part_manifest = part_manifest;
  return media::open_image_sink(options.output, sink);
}

std::size_t frame_count(double duration, double fps, double time_scale) {
  const double intervals = duration * fps / time_scale;
  return static_cast<std::size_t>(std::floor(intervals + 1e-9 * std::max(1.0, intervals))) + 1;
}

double frame_time(std::size_t frame, double fps, double time_scale) {
  return static_cast<double>(frame) * time_scale / fps;
}

double font_scale_option(double value) {
  if (!(value >= kMinFontScale && value <= kMaxFontScale)) {
    throw InputError("--font-scale: expected a text scale from " + printf_number(kMinFontScale) +
                     " to " + printf_number(kMaxFontScale) + ", got " + printf_number(value));
  }
  return value;
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
                     printf_number(plan.scene.duration) + " s at " +
                     printf_number(plan.settings.fps) + " fps and time scale " +
                     printf_number(plan.settings.time_scale) + " makes more than " +
                     printf_number(kMaxFrames) + " frames");
  }
  plan.total_frames = frame_count(plan.scene.duration, plan.settings.fps, plan.settings.time_scale);
  plan.frames = options.frames ? parse_frame_range(*options.frames, plan.total_frames)
                               : FrameRange{0, plan.total_frames};
  return plan;
}

}  // namespace tumble::app
