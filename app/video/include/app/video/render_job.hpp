#pragma once
/// @file A scene as a video: the plan (scene, settings, frame range, all checked before any mesh
/// is read), the job that steps the simulation frame by frame and draws it, and the output.
///
/// Frames are sampled from the simulation at the video's frame rate: frame k shows the state
/// at simulated time t_k = k * time_scale / fps. The simulation keeps its own dt; it is stepped
/// while its next step ends at or before t_k, so when dt does not divide the frame interval a
/// frame shows the last state at or before t_k (the overlay prints the time actually shown).

#include <cstddef>
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app/scene/render_settings.hpp"
#include "app/scene/scene.hpp"
#include "base/image.hpp"
#include "render/draw_list.hpp"
#include "render/renderer.hpp"

namespace tumble::engine {
class Simulation;
}  // namespace tumble::engine

namespace tumble::media {
class ImageSink;
}  // namespace tumble::media

namespace tumble::render {
class Renderer;
}  // namespace tumble::render

namespace tumble::app {

/// What the commands that write a video of a scene (`render`, `compare`) are asked alike.
struct VideoOptions {
  std::filesystem::path scene;
  std::filesystem::path output;       ///< "dir/" (PNG sequence), .mp4, .webm or .gif
  std::optional<std::string> size;    ///< "WIDTHxHEIGHT"
  std::optional<double> fps;          ///< video frames per second
  std::optional<std::string> frames;  ///< "A:B", half-open
  std::optional<double> time_scale;   ///< simulated seconds per second of video
  std::optional<double> font_scale;   ///< overlay text size relative to the frame's own
  std::optional<bool> lod;            ///< --lod on|off
  std::optional<std::string> shard;   ///< "I/N": the I-th of N contiguous parts of the frames
  bool quiet = false;
};

/// What `tumble render` was asked to do. Options given here override the scene.
struct RenderOptions : VideoOptions {
  std::optional<std::string> integrator;
  std::optional<double> dt;
  std::optional<std::string> antialiasing;  ///< "off", "fxaa" or samples per pixel
  bool no_overlay = false;
  /// A robot file (robot_render.hpp): the geometry of the computed inertials (--from) and
  /// where package:// paths lead (--package-path NAME=DIR).
  std::optional<std::string> robot_from;
  std::vector<std::string> package_paths;
};

/// A renderer of width x height pixels anti-aliased as `antialiasing` says, drawing big meshes
/// from their simplified copies when `lod`.
render::RendererOptions renderer_options(const Antialiasing& antialiasing, int width, int height,
                                         bool lod);

/// A half-open range [first, end) of frame numbers.
struct FrameRange {
  std::size_t first = 0;
  std::size_t end = 0;
};

/// Frames in a video of `duration` simulated seconds: floor(duration * fps / time_scale) + 1
/// (frame 0 is the initial state; a product within 1e-9 of a whole number counts as it).
std::size_t frame_count(double duration, double fps, double time_scale);

/// The simulated time frame `frame` shows, k * time_scale / fps.
double frame_time(std::size_t frame, double fps, double time_scale);

/// Checks a --font-scale value (kMinFontScale to kMaxFontScale, as render.font_scale) and
/// returns it. Throws tumble::InputError naming --font-scale (render, compare and view).
double font_scale_option(double value);

/// Parses "WIDTHxHEIGHT" (whole numbers, 1 to 8192). Throws tumble::InputError naming --size.
std::pair<int, int> parse_frame_size(const std::string& text);

/// Parses "A:B" (either end may be left out: ":B" is 0:B, "A:" is A:total) and checks
/// 0 <= A < B <= total. Throws tumble::InputError naming --frames.
FrameRange parse_frame_range(const std::string& text, std::size_t total);

/// Everything decided before any mesh is read or any output opened.
struct RenderPlan {
  SceneDescription scene;   ///< with --integrator and --dt applied
  RenderSettings settings;  ///< the scene's `render` object with the options applied
  std::size_t total_frames = 0;
  FrameRange frames;  ///< the frames to write
};

/// Loads the scene and checks every option. Throws tumble::InputError.
RenderPlan plan_render(const RenderOptions& options);

/// A running render: the compiled scene, its simulation, the renderer and the frame builder.
/// Frames are visited in order; every frame time is observed from the start, drawn or not, so a
/// range of frames is identical to the same frames of a full render.
class RenderJob {
 public:
  /// Imports the meshes and creates the renderer. Throws tumble::InputError (scene) or
  /// std::runtime_error (no GL context).
  explicit RenderJob(const RenderPlan& plan);
  /// Same, drawing with `renderer` (the caller's, which must outlive the job; its size is the
  /// caller's business): several jobs can share one GL context, and their draw lists' meshes
  /// are valid in it. Throws tumble::InputError (scene).
  RenderJob(const RenderPlan& plan, render::Renderer& renderer);
  /// Same, with the scene already compiled (from a plan that differs from this one at most in
  /// its simulation settings, which are taken from `plan`): runs of one scene under several
  /// integrators read its meshes once. Throws tumble::InputError (an integrator that cannot
  /// take a body).
  RenderJob(const RenderPlan& plan, const CompiledScene& compiled, render::Renderer& renderer);
  ~RenderJob();
  RenderJob(const RenderJob&) = delete;
  RenderJob& operator=(const RenderJob&) = delete;

  /// Steps the simulation to frame `frame`'s time, observing every frame time on the way.
  /// Frames never go back. After a blow-up the simulation stays at its last good state.
  void advance_to(std::size_t frame);

  /// Draws the current state into `image` (storage reused).
  void draw(Image& image);

  /// The draw list of the current state (what draw() renders).
  render::DrawList build() const;

  const engine::Simulation& simulation() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Opens the output of `options` (its name and --size) for frames of `settings`' size before
/// anything is rendered; videos need even sides, and the output may not be one of `inputs`
/// (scene_inputs: the scene and its meshes). Throws tumble::InputError naming the path (unknown
/// kind, odd sides, an input or a device as the output, filesystem, ffmpeg). A non-empty
/// `part_manifest` makes the output a shard's part (media::SinkOptions::part_manifest).
std::unique_ptr<media::ImageSink> open_render_output(
    const VideoOptions& options, const RenderSettings& settings, std::size_t first_frame,
    const std::vector<std::filesystem::path>& inputs, const std::string& part_manifest = {});

/// The whole render into options.output (`tumble render`'s job): the plan and the output, both
/// checked before any mesh is read (a --shard writes its part and manifest), then every frame
/// time from 0 visited and the frames of the range drawn and written, a bar on `err` with
/// `progress`, a blow-up warning on `err` and the summary line on `out` unless options.quiet.
/// Returns 0, kExitBlowUp (the output complete, later frames holding the last good state) or
/// kExitInterrupted (when `interrupted` said so between frames; nothing is left under the output
/// name). Throws tumble::InputError for bad input and ffmpeg failures, std::runtime_error when no
/// GL context can be made.
int write_render(const RenderOptions& options, const std::function<bool()>& interrupted,
                 std::ostream& out, std::ostream& err, bool progress);

}  // namespace tumble::app
