#include "app/commands/view_command.hpp"

#include <CLI/CLI.hpp>

#include "app/support/exit_status.hpp"
#include "command_line.hpp"
#include "video_options_cli.hpp"

namespace tumble::app {

CLI::App& add_view_command(CLI::App& cli, ViewOptions& options) {
  CLI::App& view = *cli.add_subcommand(kViewSummary.name, kViewSummary.summary);
  view.footer(
      "Keys: Space play/pause, Right step, Backspace reset, - and = slower/faster, Ctrl+P "
      "screenshot, Ctrl+R record, Ctrl+O open, F1 help, Esc/Ctrl+Q quit. Drag to orbit, wheel "
      "to zoom, drop a file to open it. The window is resizable. Needs a display (X11; xvfb-run "
      "works). Exit status: 0, "
      "1 for bad options or no display, 130 on Ctrl-C or SIGTERM (a recording in progress is "
      "discarded); scene and mesh errors show in the window.");
  view.add_option_function<std::string>(
          "FILE", [&](const std::string& value) { options.file = value; },
          "Scene (.json), mesh, or robot file (.urdf, .sdf, MJCF .xml: its links and their "
          "stated and computed inertials; default: the T-handle demo)")
      ->type_name("FILE");
  view.add_option("--from", options.robot_from,
                  "A robot: the geometry its computed inertials come from, as tumble inertials "
                  "--from (default collision); links are drawn from their visual geometry")
      ->check(CLI::IsMember({"collision", "visual"}))
      ->option_text("collision|visual");
  view.add_option("--package-path", options.package_paths,
                  "A robot: where package://NAME/ (and SDF model://NAME/) lead; repeatable")
      ->allow_extra_args(false)
      ->option_text("NAME=DIR");
  view.add_option_function<std::string>(
          "--size", [&](const std::string& value) { options.size = value; },
          "Window size WxH in pixels at the start (default 1280x720; the window is resizable)")
      ->type_name("WxH");
  view.add_option_function<std::string>(
          "--script", [&](const std::string& value) { options.script = value; },
          "Timed key and mouse events to play (one `TIME VERB ARGS` per line: key, keydown, "
          "keyup, type, move, click, press, release, drag, wheel, drop, screenshot, resize, quit)")
      ->type_name("FILE");
  view.add_option_function<std::string>(
          "--output-dir", [&](const std::string& value) { options.output_dir = value; },
          "Folder for screenshots and recordings (default: the working directory)")
      ->type_name("DIR");
  view.add_option_function<std::string>(
          "--integrator", [&](const std::string& value) { options.integrator = value; },
          "Integrator to start with (default: the scene's)")
      ->type_name("NAME");
  view.add_option_function<double>(
          "--dt", [&](double value) { options.dt = value; }, "Time step to start with (s)")
      ->type_name("S");
  view.add_option_function<double>(
          "--time-scale", [&](double value) { options.time_scale = value; },
          "Simulated seconds per real second (default 1)")
      ->type_name("S");
  add_font_scale_option(view, options.font_scale);
  view.add_flag("--paused", options.paused, "Start paused");
  view.add_flag("--allow-overlap", options.allow_overlap,
                "A mesh opened on its own counts overlapping parts whole (their shared volume "
                "twice), as tumble inspect --overlap sum; by default it is their exact union");
  view.add_option_function<double>(
          "--exit-after", [&](double value) { options.exit_after = value; },
          "Quit after S seconds of wall time (of frames with --frame-clock)")
      ->type_name("S");
  view.add_flag("--frame-clock", options.frame_clock,
                "Time by frames drawn, not the wall clock: every frame is 1/30 s of the viewer's "
                "time however long it takes (script times, the simulation, recordings, "
                "--exit-after), so a scripted run is the same on a loaded machine");
  view.add_flag("--stats", options.stats,
                "On exit, print frames drawn, frames per second and the frame-time median and "
                "95th percentile, then the last frame's window size, text size and panel width");
  return view;
}

int run_view(const ViewOptions& options, std::ostream& out, std::ostream& err) {
  return run_guarded("view", err, [&] { return run_viewer_window(options, out, err); });
}

}  // namespace tumble::app
