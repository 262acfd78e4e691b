// `tumble render`: scene in, video or PNG frames out.
//
// Order of work, so that mistakes cost nothing: options and scene are checked, then the output
// is opened (an unwritable directory, an unknown extension or a missing ffmpeg fail before any
// mesh is read), then meshes are imported and frames rendered. The sinks write to a temporary
// name and rename on finish(); every failure or interruption destroys the sink unfinished,
// which removes the temporary, so nothing half-written is ever left under the output name.
#include "app/commands/render_command.hpp"

#include <chrono>
#include <ostream>
#include <string>

#include <CLI/CLI.hpp>

#include "app/analysis/blow_up.hpp"
#include "app/support/exit_status.hpp"
#include "app/support/interrupt_guard.hpp"
#include "app/support/printf_number.hpp"
#include "app/support/progress_bar.hpp"
#include "app/video/video_part.hpp"
#include "command_line.hpp"
#include "engine/simulation/simulation.hpp"
#include "media/image_sink.hpp"
#include "video_options_cli.hpp"

namespace tumble::app {
namespace {

int report_interrupted(const InterruptGuard& guard, const RenderOptions& options,
                       std::ostream& err) {
  guard.report(err, "render", options.output.string());
  return kExitInterrupted;
}

/// Renders the plan into its output; returns the exit status. Throws on errors.
int render_scene(const RenderOptions& options, const InterruptGuard& guard, std::ostream& out,
                 std::ostream& err, bool progress) {
  const auto start = std::chrono::steady_clock::now();

  // Options and scene, then the output: both fail before any mesh is read.
  RenderPlan plan = plan_render(options);
  nlohmann::json job_options = frame_settings_json(plan.settings);
  job_options["integrator"] = plan.scene.integrator;
  job_options["dt"] = plan.scene.dt;
  const std::string manifest = shard_video_frames(options, "render", plan.scene, plan.total_frames,
                                                  job_options, plan.frames);
  std::unique_ptr<media::ImageSink> sink = open_render_output(
      options, plan.settings, plan.frames.first, scene_inputs(plan.scene), manifest);

  // Meshes, simulation, renderer.
  RenderJob job(plan);
  const engine::Simulation& simulation = job.simulation();

  // Every frame time from 0 is visited (cheap: step and observe); frames in the range are
  // drawn and written.
  const FrameRange range = plan.frames;
  ProgressBar bar(err, range.end - range.first, "frames", progress);
  Image image;
  for (std::size_t frame = 0; frame < range.end; ++frame) {
    if (guard.interrupted()) break;
    job.advance_to(frame);
    if (frame < range.first) continue;
    job.draw(image);
    sink->write_taking(image);  // the next draw fills a recycled buffer: no copy per frame
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
        << "; later frames hold the last good state (t = "
        << printf_number(simulation.time(), "%.9g") << " s)\n";
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

CLI::App& add_render_command(CLI::App& cli, RenderOptions& options) {
  CLI::App& render = *cli.add_subcommand(kRenderSummary.name, kRenderSummary.summary);
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
      .add_option_function<std::string>(
          "--aa", [&](const std::string& value) { options.antialiasing = value; },
          "Anti-aliasing: fxaa (default; a post-process filter, 1.05-1.3x the time), off, or "
          "multisampling with N samples per pixel (2-16, 4 max on llvmpipe, ~2.3x the time)")
      ->type_name("fxaa|off|N");
  render.add_flag("--no-overlay", options.no_overlay,
                  "No text or plots: title, integrator, time and drift plots are left out");
  return render;
}

int run_render(const RenderOptions& options, std::ostream& out, std::ostream& err) {
  const bool progress = !options.quiet && ProgressBar::on_terminal(err);
  const InterruptGuard guard;
  // An interruption under way wins over the error it caused (ffmpeg shares the terminal's
  // SIGINT and may fail first).
  return run_guarded(
      "render", err, [&] { return render_scene(options, guard, out, err, progress); },
      [&] { return guard.interrupted() ? report_interrupted(guard, options, err) : -1; });
}

}  // namespace tumble::app
