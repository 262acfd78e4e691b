// A running render: the compiled scene, its simulation, the renderer and the frame builder;
// and `tumble render`'s whole job over it.
//
// Order of work, so that mistakes cost nothing: options and scene are checked, then the output
// is opened (an unwritable directory, an unknown extension or a missing ffmpeg fail before any
// mesh is read), then meshes are imported and frames rendered. The sinks write to a temporary
// name and rename on finish(); every failure or interruption destroys the sink unfinished,
// which removes the temporary, so nothing half-written is ever left under the output name.
#include <chrono>
#include <optional>
#include <ostream>
#include <stdexcept>

#include "app/analysis/blow_up.hpp"
#include "app/frame/frame_builder.hpp"
#include "app/support/exit_status.hpp"
#include "app/support/printf_number.hpp"
#include "app/support/progress_bar.hpp"
#include "app/video/render_job.hpp"
#include "app/video/video_part.hpp"
#include "base/errors.hpp"
#include "engine/simulation/simulation.hpp"
#include "media/image_sink.hpp"
#include "render/renderer.hpp"

namespace tumble::app {

render::RendererOptions renderer_options(const Antialiasing& antialiasing, int width, int height,
                                         bool lod) {
  render::RendererOptions options{width, height, antialiasing.samples, lod};
  if (antialiasing.mode == Antialiasing::Mode::kFxaa) {
    options.filter = render::AntialiasingFilter::fxaa;
  }
  return options;
}

using tumble::InputError;

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
        own_renderer(shared != nullptr ? nullptr
                                       : std::make_unique<render::Renderer>(
                                             renderer_options(settings.antialiasing, settings.width,
                                                              settings.height, settings.lod))),
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
    : impl_(std::make_unique<Impl>(
          plan,
          [&] {
            CompiledScene copy = compiled;
            copy.settings = simulation_settings(plan.scene);
            return copy;
          }(),
          &renderer)) {}

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

void RenderJob::draw(Image& image) {
  impl_->renderer.render(build(), image);
}

render::DrawList RenderJob::build() const {
  return impl_->builder.build(*impl_->simulation);
}

const engine::Simulation& RenderJob::simulation() const {
  return *impl_->simulation;
}

namespace {

/// Visits every frame time from 0 to the range's end, drawing and writing the frames of the
/// range; stops early when `interrupted` says so (then returns false).
bool write_render_frames(RenderJob& job, FrameRange range, media::ImageSink& sink,
                         const std::function<bool()>& interrupted, std::ostream& err,
                         bool progress) {
  ProgressBar bar(err, range.end - range.first, "frames", progress);
  Image image;
  for (std::size_t frame = 0; frame < range.end; ++frame) {
    if (interrupted && interrupted()) return false;
    job.advance_to(frame);  // cheap for frames before the range: step and observe
    if (frame < range.first) continue;
    job.draw(image);
    sink.write_taking(image);  // the next draw fills a recycled buffer: no copy per frame
    bar.update(frame + 1 - range.first);
  }
  bar.clear();
  return true;
}

void print_render_summary(const RenderOptions& options, std::size_t frames, double seconds,
                          std::ostream& out) {
  out << "tumble render: " << frames << (frames == 1 ? " frame" : " frames") << " written to '"
      << options.output.string() << "' in " << printf_number(seconds, "%.2f") << " s ("
      << printf_number(seconds > 0.0 ? static_cast<double>(frames) / seconds : 0.0, "%.1f")
      << " frames/s)\n";
}

}  // namespace

int write_render(const RenderOptions& options, const std::function<bool()>& interrupted,
                 std::ostream& out, std::ostream& err, bool progress) {
  const auto start = std::chrono::steady_clock::now();

  // Options and scene, then the output: both fail before any mesh is read.
  RenderPlan plan = plan_render(options);  // a --shard narrows plan.frames to its part
  nlohmann::json job_options = frame_settings_json(plan.settings);
  job_options["integrator"] = plan.scene.integrator;
  job_options["dt"] = plan.scene.dt;
  const std::string manifest = shard_video_frames(options, "render", plan.scene, plan.total_frames,
                                                  job_options, plan.frames);
  std::unique_ptr<media::ImageSink> sink = open_render_output(
      options, plan.settings, plan.frames.first, scene_inputs(plan.scene), manifest);

  // Meshes, simulation, renderer; then the frames.
  RenderJob job(plan);
  if (!write_render_frames(job, plan.frames, *sink, interrupted, err, progress)) {
    sink.reset();  // removes the temporary
    return kExitInterrupted;
  }
  sink->finish();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  // A blow-up still gives a whole video (the last good state held), with a warning and status 3.
  int status = 0;
  const engine::Simulation& simulation = job.simulation();
  if (simulation.blow_up()) {
    err << "tumble render: warning: blow-up: " << describe_blow_up(simulation)
        << "; later frames hold the last good state (t = "
        << printf_number(simulation.time(), "%.9g") << " s)\n";
    status = kExitBlowUp;
  }
  if (!options.quiet) print_render_summary(options, sink->frames(), seconds, out);
  return status;
}

}  // namespace tumble::app
