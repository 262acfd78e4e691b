// `tumble render`: the options; the job is app/video/render_job.hpp (write_render).
#include "app/commands/render_command.hpp"

#include <ostream>
#include <string>

#include <CLI/CLI.hpp>

#include "app/support/exit_status.hpp"
#include "app/support/interrupt_guard.hpp"
#include "app/support/progress_bar.hpp"
#include "app/video/robot_picture.hpp"
#include "app/video/robot_render.hpp"
#include "command_line.hpp"
#include "video_options_cli.hpp"

namespace tumble::app {

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
                  "No text or plots: title, integrator, time and drift plots are left out (a "
                  "robot: no legend)");
  render.get_option("SCENE")->description(
      "Scene file (JSON), or a robot file (.urdf, .sdf, MJCF .xml) drawn as one .png");
  render
      .add_option_function<std::string>(
          "--from", [&](const std::string& value) { options.robot_from = value; },
          "A robot: the geometry its computed inertials come from, as tumble inertials --from "
          "(default collision); links are drawn from their visual geometry")
      ->check(CLI::IsMember({"collision", "visual"}))
      ->option_text("collision|visual");
  render
      .add_option("--package-path", options.package_paths,
                  "A robot: where package://NAME/ (and SDF model://NAME/) lead; repeatable")
      ->expected(1)  // one NAME=DIR each time (as every render option: tumble farm reads one)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
      ->option_text("NAME=DIR");
  return render;
}

int run_render(const RenderOptions& options, std::ostream& out, std::ostream& err) {
  const bool progress = !options.quiet && ProgressBar::on_terminal(err);
  const InterruptGuard guard;
  // An interruption under way wins over the error it caused (ffmpeg shares the terminal's
  // SIGINT and may fail first).
  const auto report = [&] {
    guard.report(err, "render", options.output.string());
    return kExitInterrupted;
  };
  if (is_robot_file(options.scene)) {
    return run_guarded("render", err, [&] { return write_robot_render(options, out); });
  }
  return run_guarded(
      "render", err,
      [&] {
        const int status = write_render(
            options, [&] { return guard.interrupted(); }, out, err, progress);
        return status == kExitInterrupted ? report() : status;
      },
      [&] { return guard.interrupted() ? report() : -1; });
}

}  // namespace tumble::app
