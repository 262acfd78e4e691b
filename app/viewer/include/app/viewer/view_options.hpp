#pragma once
/// @file What `tumble view` is asked to do, and the window that does it (app/viewer/window/,
/// built when the TUMBLE_VIEWER option is on, the default where SDL2 is found).

#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace tumble::app {

/// What `tumble view` was asked to do.
struct ViewOptions {
  std::optional<std::filesystem::path> file;    ///< scene (.json) or mesh; default: the demo
  std::optional<std::string> size;              ///< "WIDTHxHEIGHT" of the window
  std::optional<std::filesystem::path> script;  ///< timed input events (see viewer_input.hpp)
  std::filesystem::path output_dir = ".";       ///< screenshots and recordings
  std::optional<std::string> integrator;
  std::optional<double> dt;
  bool allow_overlap = false;  ///< a mesh opened on its own may have overlapping parts
  /// A robot file: the geometry of its computed inertials ("collision" or "visual").
  std::string robot_from = "collision";
  std::vector<std::string> package_paths;  ///< a robot file's `--package-path NAME=DIR`
  std::optional<double> time_scale;
  std::optional<double> font_scale;  ///< panels' and overlay's text; default: the scene's
  bool paused = false;
  std::optional<double> exit_after;  ///< seconds of the viewer's clock, then quit
  bool stats = false;                ///< print frame-time statistics on exit
  /// The viewer's clock counts frames, each 1/kRecordFps s however long it takes to draw, in
  /// place of the wall clock: script times, the simulation, recordings and exit_after then
  /// depend on the frames drawn alone (reproducible scripted runs on a loaded machine).
  bool frame_clock = false;
};

/// Whether this build has the windowed viewer.
bool viewer_available();

/// The scene `tumble view` opens when given none (the default demo), if it is found.
std::optional<std::filesystem::path> default_view_scene();

/// Runs the viewer's window until it closes. Returns 0, or 1 with one line on `err` when the
/// options are wrong, there is no display, or this build has no viewer. Scene and mesh errors
/// show in the window, which keeps running. SIGINT or SIGTERM closes the window at the end of
/// the frame and returns 130 with one line on `err`, "tumble view: interrupted by SIGINT",
/// adding "; recording discarded, nothing written to 'PATH'" when a recording was in progress
/// (its temporary output is removed; a recording is finished only by stopping it or quitting).
int run_viewer_window(const ViewOptions& options, std::ostream& out, std::ostream& err);

}  // namespace tumble::app
