// `tumble compare`'s job: one scene, several integrators, one video.
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
#include "app/video/compare_job.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <ostream>
#include <stdexcept>

#include "app/analysis/blow_up.hpp"
#include "app/scene/option_lists.hpp"
#include "app/support/exit_status.hpp"
#include "app/support/printf_number.hpp"
#include "app/support/progress_bar.hpp"
#include "app/video/compare_panels.hpp"
#include "app/video/image_compositing.hpp"
#include "app/video/video_part.hpp"
#include "base/errors.hpp"
#include "engine/dynamics/integrators.hpp"
#include "engine/simulation/reference_motion.hpp"
#include "engine/simulation/simulation.hpp"
#include "media/image_sink.hpp"
#include "render/renderer.hpp"

namespace tumble::app {
namespace {

using render::Rgba;
using tumble::InputError;

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

std::string blow_up_time(const engine::BlowUp& blow_up) {
  return printf_number(blow_up.time, "%.4g");
}

std::string blow_up_text(const engine::BlowUp& blow_up) {
  return "blew up at t = " + blow_up_time(blow_up) + " s";
}

/// What a run's tile says: its integrator, dt and time, and when it blew up.
TileText tile_text(const Run& run) {
  const engine::Simulation& simulation = run.job->simulation();
  TileText text{run.integrator, printf_number(run.plan.scene.dt, "%g"),
                printf_number(simulation.time(), "%.3f"), ""};
  if (const auto& blow_up = simulation.blow_up()) text.blow_up = blow_up_time(*blow_up);
  return text;
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
  legend.lines.push_back("t = " + printf_number(reference.job->simulation().time(), "%.3f") + " s");
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
  const RenderSettings& settings = reference.plan.settings;
  fit_legend_panel(legend, settings.width, settings.height, settings.font_scale);
  frame.panels.push_back(std::move(legend));
  return frame;
}

/// The runs of a comparison and how they share the frame.
struct Comparison {
  CompareLayout layout = CompareLayout::kGrid;
  std::vector<Run> runs;
  std::optional<Run> reference;   ///< the overlay's grey ghost
  RenderSettings frame_settings;  ///< the whole frame's
  FrameRange range;
  GridLayout grid;  ///< where the grid's tiles go
};

/// Checks the integrators and the layout and plans every run (scene and options checked), each
/// drawing at its tile's size in a grid and with no panel of its own in the overlay.
Comparison plan_comparison(const CompareOptions& options) {
  // The integrators, with a colour each in the overlay.
  Comparison comparison;
  const std::vector<std::string> integrators = comparison_integrators(options.integrators);
  comparison.layout = parse_compare_layout(options.layout);
  const bool grid = comparison.layout == CompareLayout::kGrid;
  if (!grid && integrators.size() > kRunPalette.size()) {
    throw InputError("--layout overlay: at most " + std::to_string(kRunPalette.size()) +
                     " integrators have a colour of their own, got " +
                     std::to_string(integrators.size()));
  }

  // Every run planned as `tumble render` would, the frame taken from the first.
  for (const std::string& integrator : integrators) {
    comparison.runs.push_back({integrator, plan_render(run_options(options, integrator)), nullptr});
  }
  comparison.frame_settings = comparison.runs.front().plan.settings;
  comparison.range = comparison.runs.front().plan.frames;
  const RenderSettings& frame = comparison.frame_settings;

  // The tiles, and what each run draws.
  if (grid) comparison.grid = grid_layout(comparison.runs.size(), frame.width, frame.height);
  for (Run& run : comparison.runs) {
    run.plan.settings.show.overlay = true;  // the labels are the point of a comparison
    if (grid) {
      run.plan.settings.width = comparison.grid.tile_width;
      run.plan.settings.height = comparison.grid.tile_height;
    } else {
      run.plan.settings.show.overlay = false;  // one legend instead
      run.plan.settings.show.inertia_ellipsoid = false;
    }
  }
  return comparison;
}

/// The renderer every run's job shares: tile-sized in a grid, frame-sized in the overlay.
render::RendererOptions shared_renderer_options(const Comparison& comparison) {
  const bool grid = comparison.layout == CompareLayout::kGrid;
  const RenderSettings& frame = comparison.frame_settings;
  return renderer_options(frame.antialiasing, grid ? comparison.grid.tile_width : frame.width,
                          grid ? comparison.grid.tile_height : frame.height, frame.lod);
}

/// Starts every run's job on the compiled scene, and in the overlay the reference's
/// (engine::ReferenceMotion: exact or dopri, run as a job).
void start_jobs(const CompareOptions& options, const CompiledScene& compiled,
                render::Renderer& renderer, Comparison& comparison) {
  for (Run& run : comparison.runs) {
    run.job = std::make_unique<RenderJob>(run.plan, compiled, renderer);
  }
  if (comparison.layout != CompareLayout::kOverlay) return;
  const Run& first = comparison.runs.front();
  const engine::ReferenceMotion motion(first.job->simulation().bodies(),
                                       first.job->simulation().initial_states());
  Run& reference = comparison.reference.emplace();
  reference.integrator = engine::integrator_info(motion.integrator()).name;
  reference.plan = plan_render(run_options(options, reference.integrator));
  reference.plan.settings = first.plan.settings;
  reference.plan.scene.tolerance = motion.tolerance();
  reference.plan.scene.absolute_tolerance.reset();  // the reference's own: relative only
  reference.job = std::make_unique<RenderJob>(reference.plan, compiled, renderer);
}

/// The grid frame: each run's panel drawn with the first run's camera and copied into its
/// tile, over the gap grey.
void draw_grid_frame(const Comparison& comparison, render::Renderer& renderer, Image& tile,
                     Image& frame) {
  const GridLayout& grid = comparison.grid;
  fill_grey(frame, comparison.frame_settings.width, comparison.frame_settings.height, kGapGrey);
  // Every tile with the first run's camera and the same drift scales.
  std::vector<render::DrawList> lists;
  std::vector<TileText> texts;
  for (std::size_t i = 0; i < comparison.runs.size(); ++i) {
    lists.push_back(comparison.runs[i].job->build());
    lists.back().camera = lists.front().camera;
    texts.push_back(tile_text(comparison.runs[i]));
  }
  fit_tile_panels(lists, texts, grid.tile_width, grid.tile_height);
  share_plot_scales(lists);
  for (std::size_t i = 0; i < comparison.runs.size(); ++i) {
    const render::DrawList& list = lists[i];
    renderer.render(list, tile);
    const auto column = static_cast<int>(i % static_cast<std::size_t>(grid.columns));
    const auto row = static_cast<int>(i / static_cast<std::size_t>(grid.columns));
    paste_tile(tile, frame, grid.left + column * grid.tile_width,
               grid.top + row * grid.tile_height);
  }
}

/// Every frame time from 0 is visited by every run; frames in the range are drawn into `sink`.
/// Stops early when interrupted.
void draw_frames(Comparison& comparison, render::Renderer& renderer, media::ImageSink& sink,
                 const std::function<bool()>& interrupted, std::ostream& err, bool progress) {
  const FrameRange& range = comparison.range;
  ProgressBar bar(err, range.end - range.first, "frames", progress);
  Image frame;
  Image tile;
  for (std::size_t index = 0; index < range.end; ++index) {
    if (interrupted && interrupted()) break;
    for (Run& run : comparison.runs) run.job->advance_to(index);
    if (comparison.reference) comparison.reference->job->advance_to(index);
    // The frame before the range is drawn and dropped: the first frame a renderer draws for a
    // grid differs from later ones in a few hundred pixels of text (the panel's fit runs before
    // the font is at its size), so without it --frames A:B and --shard would not match a full
    // run's frame A.
    if (index + 1 < range.first) continue;
    if (comparison.layout == CompareLayout::kGrid) {
      draw_grid_frame(comparison, renderer, tile, frame);
    } else {
      renderer.render(overlay_frame(comparison.runs, *comparison.reference), frame);
    }
    if (index < range.first) continue;
    sink.write(frame);
    bar.update(index + 1 - range.first);
  }
  bar.clear();
}

/// One warning line per blown-up run, the overlay's reference included (the output is
/// complete: those runs hold their last good state); kExitBlowUp when there was one, else 0.
int warn_blow_ups(const Comparison& comparison, std::ostream& err) {
  int status = 0;
  const auto warn = [&](const Run& run, const std::string& who) {
    const engine::Simulation& simulation = run.job->simulation();
    if (!simulation.blow_up()) return;
    err << "tumble compare: warning: " << who << " blew up: " << describe_blow_up(simulation)
        << "; its later frames hold the last good state (t = "
        << printf_number(simulation.time(), "%.9g") << " s)\n";
    status = kExitBlowUp;
  };
  for (const Run& run : comparison.runs) warn(run, run.integrator);
  if (comparison.reference) {
    warn(*comparison.reference, "the reference (" + comparison.reference->integrator + ")");
  }
  return status;
}

void print_summary(const CompareOptions& options, const Comparison& comparison, std::size_t frames,
                   double seconds, std::ostream& out) {
  const GridLayout& grid = comparison.grid;
  out << "tumble compare: " << comparison.runs.size() << " integrators, " << frames
      << (frames == 1 ? " frame" : " frames") << " ("
      << (comparison.layout == CompareLayout::kGrid
              ? "grid " + std::to_string(grid.columns) + "x" + std::to_string(grid.rows)
              : "overlay on " + comparison.reference->integrator)
      << ") written to '" << options.output.string() << "' in " << printf_number(seconds, "%.2f")
      << " s\n";
}

}  // namespace

int write_comparison(const CompareOptions& options, const std::function<bool()>& interrupted,
                     std::ostream& out, std::ostream& err, bool progress) {
  const auto start = std::chrono::steady_clock::now();

  // Integrators, layout, scene and options; then the output. All fail before any mesh is read.
  Comparison comparison = plan_comparison(options);
  const RenderPlan& first = comparison.runs.front().plan;
  nlohmann::json job_options = frame_settings_json(comparison.frame_settings);
  job_options["integrators"] = comparison_integrators(options.integrators);
  job_options["layout"] = options.layout;
  job_options["dt"] = first.scene.dt;
  const std::string manifest = shard_video_frames(
      options, "compare", first.scene, first.total_frames, job_options, comparison.range);
  std::unique_ptr<media::ImageSink> sink =
      open_render_output(options, comparison.frame_settings, comparison.range.first,
                         scene_inputs(first.scene), manifest);

  // One renderer for every job; the scene is compiled (its meshes read) once, as the runs
  // differ only in their settings.
  render::Renderer renderer(shared_renderer_options(comparison));
  const CompiledScene compiled =
      compile_scene(comparison.runs.front().plan.scene, /*keep_geometry=*/true);
  start_jobs(options, compiled, renderer, comparison);

  draw_frames(comparison, renderer, *sink, interrupted, err, progress);
  if (interrupted && interrupted()) {
    sink.reset();  // removes the temporary
    return kExitInterrupted;
  }
  sink->finish();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const int status = warn_blow_ups(comparison, err);
  if (!options.quiet) print_summary(options, comparison, sink->frames(), seconds, out);
  return status;
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

}  // namespace tumble::app
