// `tumble compare`: one scene, several integrators, one video.
//
// Design note
// - Each integrator is a `tumble render` job of its own (RenderPlan + RenderJob: simulation,
//   FrameBuilder, frame sampling), so a panel of the grid is exactly what `tumble render
//   --integrator NAME` would draw at that size, with the same camera. All jobs draw with one
//   shared Renderer (one GL context; each job uploads its own meshes into it): in the grid it
//   is tile-sized and each panel is rendered then copied into the frame on the CPU; in the
//   overlay it is frame-sized and the jobs' meshes are merged into one draw list.
// - Order of work as in `tumble render`: options, integrators and scene are checked, then the
//   output is opened, then meshes are imported and frames drawn; the sinks are atomic.
// - A run that blows up holds its last good state (RenderJob does that); the others go on and
//   the command ends with status 3 after one warning line per blown-up run.
#include "app/commands/compare_command.hpp"

#include "app/scene/option_lists.hpp"
#include "app/support/printf_number.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <memory>
#include <ostream>
#include <stdexcept>

#include <CLI/CLI.hpp>

#include "app/commands/exit_status.hpp"
#include "command_line.hpp"
#include "video_options_cli.hpp"

#include "app/analysis/blow_up.hpp"
#include "app/support/interrupt_guard.hpp"
#include "engine/input_error.hpp"
#include "engine/integrators.hpp"
#include "engine/reference_motion.hpp"
#include "engine/simulation.hpp"
#include "app/support/progress_bar.hpp"
#include "render/image_sink.hpp"
#include "render/renderer.hpp"

namespace tumble::app {
namespace {

using engine::InputError;
using render::Rgba;

/// A run's colour in the overlay, with the name the legend gives it.
struct NamedColour {
  const char* name;
  Rgba colour;
};

constexpr float kRunAlpha = 0.6f;
constexpr std::array<NamedColour, 8> kRunPalette = {{{"orange", {0.95f, 0.50f, 0.10f, kRunAlpha}},
                                                     {"green", {0.15f, 0.75f, 0.25f, kRunAlpha}},
                                                     {"magenta", {0.85f, 0.20f, 0.75f, kRunAlpha}},
                                                     {"cyan", {0.10f, 0.75f, 0.85f, kRunAlpha}},
                                                     {"yellow", {0.95f, 0.85f, 0.15f, kRunAlpha}},
                                                     {"red", {0.90f, 0.15f, 0.15f, kRunAlpha}},
                                                     {"blue", {0.20f, 0.35f, 0.95f, kRunAlpha}},
                                                     {"brown", {0.55f, 0.35f, 0.15f, kRunAlpha}}}};
constexpr Rgba kGhostColour{0.40f, 0.40f, 0.40f, 0.30f};
/// Grey level of the gaps around and between the grid's tiles and of empty tiles.
constexpr std::uint8_t kGapGrey = 24;
constexpr int kMinTileSide = 16;


/// One integrator's run: its plan and its render job.
struct Run {
  std::string integrator;
  RenderPlan plan;
  std::unique_ptr<RenderJob> job;
};

/// The `tumble render` options of one run.
RenderOptions run_options(const CompareOptions& options, const std::string& integrator) {
  RenderOptions run;
  static_cast<VideoOptions&>(run) = options;
  run.integrator = integrator;
  run.dt = options.dt;
  return run;
}

/// "rk4, dt = 0.01 s"
std::string run_title(const Run& run) {
  return run.integrator + ", dt = " + printf_number(run.plan.scene.dt, "%g") + " s";
}

std::string blow_up_text(const engine::BlowUp& blow_up) {
  return "blew up at t = " + printf_number(blow_up.time, "%.4g") + " s";
}

/// Fills `image` (resized to width x height) with an opaque grey.
void fill(render::Image& image, int width, int height, std::uint8_t grey) {
  image.width = width;
  image.height = height;
  image.rgba.assign(4 * static_cast<std::size_t>(width) * static_cast<std::size_t>(height), grey);
  for (std::size_t i = 3; i < image.rgba.size(); i += 4) image.rgba[i] = 255;
}

/// Copies `tile` into `frame` with its top-left corner at (x, y); the tile must fit.
void paste(const render::Image& tile, render::Image& frame, int x, int y) {
  const std::size_t row_bytes = 4 * static_cast<std::size_t>(tile.width);
  for (int row = 0; row < tile.height; ++row) {
    std::memcpy(frame.rgba.data() + 4 * (static_cast<std::size_t>(y + row) * frame.width + x),
                tile.rgba.data() + static_cast<std::size_t>(row) * row_bytes, row_bytes);
  }
}

/// Makes the FrameBuilder's overlay panel fit a tile: the run's integrator and dt as its
/// title, the time (and the blow-up) as its lines, and its drift plots scaled to the tile.
void fit_panel(render::DrawList& list, const Run& run, const GridLayout& grid) {
  if (list.panels.empty()) return;
  const engine::Simulation& simulation = run.job->simulation();
  render::OverlayPanel& panel = list.panels.front();
  panel.title = run_title(run);
  panel.width_px = std::min(260.0f, static_cast<float>(grid.tile_width) - 20.0f);
  panel.lines = {"t = " + printf_number(simulation.time(), "%.3f") + " s"};
  if (const auto& blow_up = simulation.blow_up()) panel.lines.push_back(blow_up_text(*blow_up));
  const float plot_height = std::clamp(0.1f * static_cast<float>(grid.tile_height), 14.0f, 50.0f);
  for (render::Plot& plot : panel.plots) plot.height_px = plot_height;
}

/// The overlay frame: the reference's stage and camera, its meshes as a grey ghost, every
/// run's meshes in its colour, and a legend panel.
render::DrawList overlay_frame(const std::vector<Run>& runs, const Run& reference) {
  render::DrawList frame = reference.job->build();
  for (render::MeshInstance& mesh : frame.meshes) mesh.colour = kGhostColour;
  frame.arrows.clear();
  frame.polylines.clear();
  frame.points.clear();
  frame.labels.clear();
  frame.panels.clear();

  render::OverlayPanel legend;
  legend.title = reference.plan.scene.name;
  legend.width_px = 300.0f;
  legend.lines.push_back(
      "t = " + printf_number(reference.job->simulation().time(), "%.3f") + " s");
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const NamedColour& colour = kRunPalette[i % kRunPalette.size()];
    for (render::MeshInstance mesh : runs[i].job->build().meshes) {
      mesh.colour = colour.colour;
      frame.meshes.push_back(mesh);
    }
    std::string line = std::string(colour.name) + ": " + run_title(runs[i]);
    if (const auto& blow_up = runs[i].job->simulation().blow_up()) {
      line += " (" + blow_up_text(*blow_up) + ")";
    }
    legend.lines.push_back(std::move(line));
  }
  legend.lines.push_back("grey ghost: " + reference.integrator + " (reference)");
  frame.panels.push_back(std::move(legend));
  return frame;
}

/// Runs the comparison into its output; returns the exit status. Throws on errors.
int compare_scene(const CompareOptions& options, const InterruptGuard& guard, std::ostream& out,
                  std::ostream& err, bool progress) {
  const auto start = std::chrono::steady_clock::now();

  // Integrators, layout, scene and options; then the output. All fail before any mesh is read.
  const std::vector<std::string> integrators = comparison_integrators(options.integrators);
  const CompareLayout layout = parse_compare_layout(options.layout);
  if (layout == CompareLayout::kOverlay && integrators.size() > kRunPalette.size()) {
    throw InputError("--layout overlay: at most " + std::to_string(kRunPalette.size()) +
                     " integrators have a colour of their own, got " +
                     std::to_string(integrators.size()));
  }
  std::vector<Run> runs;
  for (const std::string& integrator : integrators) {
    runs.push_back({integrator, plan_render(run_options(options, integrator)), nullptr});
  }
  const RenderSettings frame_settings = runs.front().plan.settings;
  const FrameRange range = runs.front().plan.frames;
  GridLayout grid;
  if (layout == CompareLayout::kGrid) {
    grid = grid_layout(runs.size(), frame_settings.width, frame_settings.height);
  }
  for (Run& run : runs) {
    run.plan.settings.show.overlay = true;  // the labels are the point of a comparison
    if (layout == CompareLayout::kGrid) {
      run.plan.settings.width = grid.tile_width;
      run.plan.settings.height = grid.tile_height;
    } else {
      run.plan.settings.show.overlay = false;  // one legend instead
      run.plan.settings.show.inertia_ellipsoid = false;
    }
  }
  std::unique_ptr<render::ImageSink> sink =
      open_render_output(options, frame_settings, range.first);

  // One renderer (tile- or frame-sized) shared by every run's job.
  const int renderer_width = layout == CompareLayout::kGrid ? grid.tile_width : frame_settings.width;
  const int renderer_height =
      layout == CompareLayout::kGrid ? grid.tile_height : frame_settings.height;
  render::Renderer renderer(
      render::RendererOptions{renderer_width, renderer_height, frame_settings.antialiasing});
  // The scene is compiled (its meshes read) once; the runs differ only in their settings.
  const CompiledScene compiled = compile_scene(runs.front().plan.scene, /*keep_geometry=*/true);
  for (Run& run : runs) run.job = std::make_unique<RenderJob>(run.plan, compiled, renderer);

  // The overlay's reference (engine::ReferenceMotion): exact or dopri, run as a job.
  std::optional<Run> reference;
  if (layout == CompareLayout::kOverlay) {
    const engine::Simulation& first = runs.front().job->simulation();
    const engine::ReferenceMotion motion(first.bodies(), first.initial_states());
    reference.emplace();
    reference->integrator = engine::integrator_info(motion.integrator()).name;
    reference->plan = plan_render(run_options(options, reference->integrator));
    reference->plan.settings = runs.front().plan.settings;
    reference->plan.scene.tolerance = motion.tolerance();
    reference->job = std::make_unique<RenderJob>(reference->plan, compiled, renderer);
  }

  // Every frame time from 0 is visited by every run; frames in the range are drawn.
  ProgressBar bar(err, range.end - range.first, "frames", progress);
  render::Image frame;
  render::Image tile;
  for (std::size_t index = 0; index < range.end; ++index) {
    if (guard.interrupted()) break;
    for (Run& run : runs) run.job->advance_to(index);
    if (reference) reference->job->advance_to(index);
    if (index < range.first) continue;
    if (layout == CompareLayout::kGrid) {
      // Each panel with the first run's camera, copied into its tile.
      fill(frame, frame_settings.width, frame_settings.height, kGapGrey);
      render::Camera camera;
      for (std::size_t i = 0; i < runs.size(); ++i) {
        render::DrawList list = runs[i].job->build();
        if (i == 0) camera = list.camera;
        list.camera = camera;
        fit_panel(list, runs[i], grid);
        renderer.render(list, tile);
        const auto column = static_cast<int>(i % static_cast<std::size_t>(grid.columns));
        const auto row = static_cast<int>(i / static_cast<std::size_t>(grid.columns));
        paste(tile, frame, grid.left + column * grid.tile_width,
              grid.top + row * grid.tile_height);
      }
    } else {
      renderer.render(overlay_frame(runs, *reference), frame);
    }
    sink->write(frame);
    bar.update(index + 1 - range.first);
  }
  bar.clear();
  if (guard.interrupted()) {
    sink.reset();  // removes the temporary
    err << "tumble compare: interrupted by " << guard.signal_name() << "; nothing written to '"
        << options.output.string() << "'\n";
    return kExitInterrupted;
  }
  sink->finish();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  // Blow-ups, the overlay's reference's included: the output is complete (those runs hold
  // their last good state); one line each.
  int status = 0;
  const auto warn = [&](const Run& run, const std::string& who) {
    const engine::Simulation& simulation = run.job->simulation();
    if (!simulation.blow_up()) return;
    err << "tumble compare: warning: " << who << " blew up: " << describe_blow_up(simulation)
        << "; its later frames hold the last good state (t = "
        << printf_number(simulation.time(), "%.9g") << " s)\n";
    status = kExitBlowUp;
  };
  for (const Run& run : runs) warn(run, run.integrator);
  if (reference) warn(*reference, "the reference (" + reference->integrator + ")");
  if (!options.quiet) {
    const std::size_t frames = sink->frames();
    out << "tumble compare: " << runs.size() << " integrators, " << frames
        << (frames == 1 ? " frame" : " frames") << " ("
        << (layout == CompareLayout::kGrid
                ? "grid " + std::to_string(grid.columns) + "x" + std::to_string(grid.rows)
                : "overlay on " + reference->integrator)
        << ") written to '" << options.output.string() << "' in " << printf_number(seconds, "%.2f")
        << " s\n";
  }
  return status;
}

}  // namespace

CLI::App& add_compare_command(CLI::App& cli, CompareOptions& options) {
  CLI::App& compare = *cli.add_subcommand(kCompareSummary.name, kCompareSummary.summary);
  compare.footer(
      "Every run uses the same dt and the same frame times as tumble render. grid: one panel "
      "per integrator, same camera, each with its energy and |L| drift plots. overlay: every "
      "run in its own translucent colour over a grey ghost of the reference (exact for "
      "torque-free scenes, otherwise dopri at tolerance " +
      printf_number(engine::kReferenceTolerance, "%g") + "). A run that blows up holds its "
      "last good state and says when. Exit status: 0 done, 1 bad scene/option/output or ffmpeg "
      "failure, 3 some run blew up (the output is still complete), 130 interrupted (nothing "
      "written).");
  add_video_options(
      compare, options,
      "Size WxH of the whole frame in pixels (default 1280x720; even for .mp4/.webm)");
  compare
      .add_option_function<std::string>(
          "--integrators", [&](const std::string& value) { options.integrators = value; },
          "Integrators to compare, comma-separated, at least two (see tumble simulate "
          "--list-integrators)")
      ->required()
      ->type_name("A,B,...");
  compare
      .add_option_function<std::string>(
          "--layout", [&](const std::string& value) { options.layout = value; },
          "grid (one panel per integrator, the default) or overlay (one view, one colour each)")
      ->type_name("grid|overlay");
  compare
      .add_option_function<double>(
          "--dt", [&](double value) { options.dt = value; },
          "Time step H in seconds of every run (default: the scene's)")
      ->type_name("H");
  return compare;
}

std::vector<std::string> comparison_integrators(const std::string& text) {
  std::vector<std::string> names;
  for (const std::string& name : split_option_list(text, "--integrators")) {
    if (std::find(names.begin(), names.end(), name) != names.end()) {
      throw InputError("--integrators: '" + name + "' is given twice");
    }
    names.push_back(name);
  }
  parse_integrator_list(text, "--integrators");  // every name known
  if (names.size() < 2) {
    throw InputError("--integrators: a comparison needs at least two integrators, got '" + text +
                     "'");
  }
  return names;
}

CompareLayout parse_compare_layout(const std::string& text) {
  if (text == "grid") return CompareLayout::kGrid;
  if (text == "overlay") return CompareLayout::kOverlay;
  throw InputError("--layout: expected grid or overlay, got \"" + text + "\"");
}

GridLayout grid_layout(std::size_t panels, int width, int height) {
  GridLayout grid;
  grid.columns = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(panels)) - 1e-9));
  grid.columns = std::max(grid.columns, 1);
  grid.rows = static_cast<int>((panels + static_cast<std::size_t>(grid.columns) - 1) /
                               static_cast<std::size_t>(grid.columns));
  grid.rows = std::max(grid.rows, 1);
  grid.tile_width = (width / grid.columns) / 2 * 2;
  grid.tile_height = (height / grid.rows) / 2 * 2;
  if (grid.tile_width < kMinTileSide || grid.tile_height < kMinTileSide) {
    throw InputError("--size: " + std::to_string(width) + "x" + std::to_string(height) +
                     " is too small for " + std::to_string(panels) + " panels in a " +
                     std::to_string(grid.columns) + "x" + std::to_string(grid.rows) +
                     " grid (each needs at least " + std::to_string(kMinTileSide) + "x" +
                     std::to_string(kMinTileSide) + " pixels)");
  }
  grid.left = (width - grid.columns * grid.tile_width) / 2;
  grid.top = (height - grid.rows * grid.tile_height) / 2;
  return grid;
}

int run_compare(const CompareOptions& options, std::ostream& out, std::ostream& err) {
  const bool progress = !options.quiet && ProgressBar::on_terminal(err);
  const InterruptGuard guard;
  // An interruption under way wins over the error it caused (ffmpeg shares the terminal's
  // SIGINT and may fail first).
  const auto interrupted = [&] {
    if (!guard.interrupted()) return -1;
    err << "tumble compare: interrupted by " << guard.signal_name() << "; nothing written to '"
        << options.output.string() << "'\n";
    return kExitInterrupted;
  };
  return run_guarded(
      "compare", err, [&] { return compare_scene(options, guard, out, err, progress); },
      interrupted);
}

}  // namespace tumble::app
