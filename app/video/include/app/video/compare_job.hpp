#pragma once
/// @file `tumble compare`'s job: one scene run with several integrators, rendered side by side
/// (beside the render job, render_job.hpp).
///
/// Every run samples the same frame times as `tumble render` (frame k shows t_k = k *
/// time_scale / fps; each run keeps the common dt). Two layouts:
///  - grid: one panel per integrator in a near-square grid, all with the same camera (the
///    first run's), each labelled with its integrator, dt and time and carrying its energy and
///    |L| drift plots;
///  - overlay: every run in one view, each in its own translucent colour, over a grey ghost of
///    a reference run (`exact` when every body is torque-free or a heavy symmetric top,
///    otherwise `dopri` at tolerance 1e-12) whose camera it uses, with a legend mapping colours to
///    integrators.
/// A run that blows up holds its last good state and says when it blew up; the others go on.

#include <cstddef>
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "app/video/render_job.hpp"

namespace tumble::app {

/// How the runs share the frame.
enum class CompareLayout { kGrid, kOverlay };

/// What `tumble compare` was asked to do. Options given here override the scene.
/// (`size` is that of the whole frame.)
struct CompareOptions : VideoOptions {
  std::string integrators;      ///< "a,b,c": at least two, all different
  std::string layout = "grid";  ///< "grid" or "overlay"
  std::optional<double> dt;     ///< common time step of every run
};

/// Splits and checks --integrators: known names, at least two, no repeats. Throws
/// tumble::InputError naming --integrators.
std::vector<std::string> comparison_integrators(const std::string& text);

/// Parses --layout ("grid" or "overlay"). Throws tumble::InputError naming --layout.
CompareLayout parse_compare_layout(const std::string& text);

/// Where the panels of a grid go in a frame.
struct GridLayout {
  int columns = 1;
  int rows = 1;
  int tile_width = 0;   ///< even, pixels
  int tile_height = 0;  ///< even, pixels
  int left = 0;         ///< x of the first column (the grid is centred in the frame)
  int top = 0;          ///< y of the first row
};

/// A near-square grid for `panels` panels in a `width` x `height` frame: ceil(sqrt(n))
/// columns and as many rows as needed (2 -> 2x1, 3 and 4 -> 2x2, 5 and 6 -> 3x2), equal tiles
/// of even sides. Throws tumble::InputError naming --size when a tile would be under 16 pixels.
GridLayout grid_layout(std::size_t panels, int width, int height);

/// The whole comparison into options.output: checks (integrators, layout, scene, options, the
/// output, all before any mesh is read), the runs stepped and drawn frame by frame, a bar on
/// `err` with `progress`, one warning line per blown-up run on `err` and the summary on `out`
/// unless options.quiet. Returns 0, kExitBlowUp (the output complete) or kExitInterrupted (when
/// `interrupted` said so; nothing left under the output name). Throws InputError for bad input
/// and ffmpeg failures.
int write_comparison(const CompareOptions& options, const std::function<bool()>& interrupted,
                     std::ostream& out, std::ostream& err, bool progress);

}  // namespace tumble::app
