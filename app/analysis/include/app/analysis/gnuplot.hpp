#pragma once
// Plots through gnuplot (a script file per drawing, PNG and SVG of each plot): the runner shared
// by bench and stability, and bench's log-log work-precision plots.

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace tumble::app {

/// One line with points of a plot.
struct PlotSeries {
  std::string title;
  std::vector<std::pair<double, double>> points;  ///< (x, y); non-positive values are left out
};

/// A log-log plot written to `file_stem`.png and `file_stem`.svg.
struct LogLogPlot {
  std::filesystem::path file_stem;
  std::string title;
  std::string x_label;
  std::string y_label;
  std::vector<PlotSeries> series;
};

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
