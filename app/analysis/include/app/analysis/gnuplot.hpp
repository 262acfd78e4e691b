#pragma once
// Plots through gnuplot (a script file per drawing, PNG and SVG of each plot): the runner shared
// by bench and stability, and bench's log-log work-precision plots.

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace tumble::app {

/// One point of a series, with an optional horizontal error bar [x_low, x_high].
struct PlotPoint {
  double x = 0.0;
  double y = 0.0;
  double x_low = 0.0;   ///< used when the plot has x_error_bars
  double x_high = 0.0;  ///< used when the plot has x_error_bars
};

/// How a series is drawn: a gnuplot colour ('#rrggbb') and point type.
struct PlotStyle {
  std::string colour = "#000000";
  int point_type = 1;
};

/// One line with points of a plot. Points with x <= 0, y < 0 or a non-finite value are left
/// out; points with y exactly 0 are drawn at the plot's floor (zero_floor) with an open marker.
struct PlotSeries {
  std::string title;
  std::vector<PlotPoint> points;
  PlotStyle style;
};

/// A log-log plot written to `file_stem`.png and `file_stem`.svg.
struct LogLogPlot {
  std::filesystem::path file_stem;
  std::string title;
  std::string x_label;
  std::string y_label;
  std::vector<PlotSeries> series;
  bool x_error_bars = false;  ///< draw [x_low, x_high] of every point
};

/// Where a plot draws its points whose y is exactly 0 (nothing to show on a log axis): a power
/// of ten a decade below its smallest positive y (1e-16 when it has none).
double zero_floor(const LogLogPlot& plot);

/// A string as a gnuplot single-quoted literal.
std::string gnuplot_quoted(const std::string& text);

/// Writes `script` to `script_file`, runs gnuplot on it, removes the file and checks the
/// `pictures` the script draws (check_pictures). Throws InputError with gnuplot's first output
/// line (or its exit status) when it fails, WriteError when a file could not be written.
void run_gnuplot(const std::string& script, const std::filesystem::path& script_file,
                 const std::vector<std::filesystem::path>& pictures);

/// Throws WriteError naming the first of `pictures` (.png or .svg) that is missing or cut
/// short: gnuplot exits 0 when the disk fills under it, leaving half a picture.
void check_pictures(const std::vector<std::filesystem::path>& pictures);

/// True when `gnuplot` runs (it is looked up on the PATH).
bool gnuplot_available();

/// The gnuplot script that draws `plots` (exposed for tests).
std::string gnuplot_script(const std::vector<LogLogPlot>& plots);

/// Writes the script to `script_file`, runs gnuplot on it and removes it (see run_gnuplot for
/// the errors); every plot's PNG and SVG is checked.
void draw_plots(const std::vector<LogLogPlot>& plots, const std::filesystem::path& script_file);

}  // namespace tumble::app
