#include "app/analysis/gnuplot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "app/support/file_write.hpp"
#include "base/errors.hpp"

namespace tumble::app {
namespace {

/// The shell-quoted form of a path.
std::string shell_quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) {
    if (c == '\'')
      out += "'\\''";
    else
      out += c;
  }
  return out + "'";
}

bool drawable(const PlotPoint& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && p.x > 0.0 && p.y >= 0.0;
}

/// The point type of the floor markers (an open triangle pointing down).
constexpr int kFloorPointType = 10;

/// The drawing commands of one plot (after `set terminal` and `set output`).
void plot_commands(std::ostream& script, const LogLogPlot& plot, std::size_t index) {
  script << "set title " << gnuplot_quoted(plot.title) << " noenhanced\n"
         << "set xlabel " << gnuplot_quoted(plot.x_label) << " noenhanced\n"
         << "set ylabel " << gnuplot_quoted(plot.y_label) << " noenhanced\n";
  std::vector<std::size_t> drawn;
  bool zeros = false;
  for (std::size_t s = 0; s < plot.series.size(); ++s) {
    std::size_t count = 0;
    for (const PlotPoint& p : plot.series[s].points) {
      count += drawable(p);
      zeros = zeros || (drawable(p) && p.y == 0.0);
    }
    if (count > 0) drawn.push_back(s);
  }
  if (drawn.empty()) {
    // Nothing positive to draw on log axes: an empty frame that says so.
    script << "set label 1 'no positive values to plot' at graph 0.5, 0.5 center\n"
           << "plot [1e-6:1] [1e-16:1] 1/0 notitle\nunset label 1\n";
    return;
  }
  if (zeros) {
    // The floor a third of a decade above the axis, so its markers show whole.
    const double floor = zero_floor(plot);
    char text[32];
    std::snprintf(text, sizeof text, "%.0e", floor);
    // In the right margin, under the key (a double-quoted string for its line breaks).
    script << "set label 2 \"open triangles:\\nerror exactly 0,\\ndrawn at " << text
           << "\" at graph 1.03, graph 0.12 left front noenhanced\nset yrange [" << floor / 2.0
           << ":*]\n";
  }
  const char* with =
      plot.x_error_bars ? "using 1:2:3:4 with xerrorlines" : "using 1:2 with linespoints";
  script << "plot ";
  for (std::size_t j = 0; j < drawn.size(); ++j) {
    const PlotSeries& series = plot.series[drawn[j]];
    const std::string block = "$p" + std::to_string(index) + "_" + std::to_string(drawn[j]);
    const auto nonzero = std::count_if(series.points.begin(), series.points.end(),
                                       [](const PlotPoint& p) { return drawable(p) && p.y > 0.0; });
    const std::string title = " title " + gnuplot_quoted(series.title) + " noenhanced";
    script << (j ? ", \\\n     " : "");
    if (nonzero > 0) {
      script << block << " " << with << " linecolor rgb " << gnuplot_quoted(series.style.colour)
             << " pointtype " << series.style.point_type << title;
    }
    if (nonzero < static_cast<std::ptrdiff_t>(series.points.size()) &&
        std::any_of(series.points.begin(), series.points.end(),
                    [](const PlotPoint& p) { return drawable(p) && p.y == 0.0; })) {
      // The series' zeros; they carry its title when it has nothing else to show.
      script << (nonzero > 0 ? ", \\\n     " : "") << block
             << "_zero using 1:2 with points linecolor rgb " << gnuplot_quoted(series.style.colour)
             << " pointtype " << kFloorPointType << " pointsize 1.6"
             << (nonzero > 0 ? " notitle" : title);
    }
  }
  script << "\n";
  if (zeros) script << "unset label 2\nset autoscale y\n";
}

/// The last `count` bytes of `file` (fewer when it is shorter); empty when it cannot be read.
std::string file_tail(const std::filesystem::path& file, std::size_t count) {
  std::ifstream in(file, std::ios::binary | std::ios::ate);
  if (!in) return {};
  const std::streamoff size = in.tellg();
  const std::streamoff start =
      std::max<std::streamoff>(0, size - static_cast<std::streamoff>(count));
  in.seekg(start);
  std::string tail(static_cast<std::size_t>(size - start), '\0');
  in.read(tail.data(), static_cast<std::streamsize>(tail.size()));
  return in ? tail : std::string();
}

/// Whether `file` is whole: a PNG ends with its IEND chunk, an SVG with its closing tag. gnuplot
/// neither complains nor fails when a write of its output fails (a full disk): it exits 0 and
/// leaves the file cut short.
bool complete_picture(const std::filesystem::path& file) {
  if (file.extension() == ".png") {
    static const std::string kIend("\0\0\0\0IEND\xae\x42\x60\x82", 12);
    return file_tail(file, kIend.size()) == kIend;
  }
  std::string tail = file_tail(file, 64);
  while (!tail.empty() && (tail.back() == '\n' || tail.back() == ' ')) tail.pop_back();
  return tail.ends_with("</svg>");
}

}  // namespace

void check_pictures(const std::vector<std::filesystem::path>& pictures) {
  for (const std::filesystem::path& picture : pictures) {
    std::error_code error;
    if (!std::filesystem::exists(picture, error)) {
      throw WriteError(picture, "gnuplot wrote no picture (is the disk full?)");
    }
    if (!complete_picture(picture)) {
      const auto size = std::filesystem::file_size(picture, error);
      throw WriteError(picture, "gnuplot stopped after " + std::to_string(error ? 0 : size) +
                                    " bytes, the picture is incomplete (is the disk full?)");
    }
  }
}

bool gnuplot_available() {
  return std::system("gnuplot --version >/dev/null 2>&1") == 0;
}

double zero_floor(const LogLogPlot& plot) {
  double smallest = INFINITY;
  for (const PlotSeries& series : plot.series) {
    for (const PlotPoint& p : series.points) {
      if (drawable(p) && p.y > 0.0) smallest = std::min(smallest, p.y);
    }
  }
  return std::isfinite(smallest) ? std::pow(10.0, std::floor(std::log10(smallest)) - 1.0) : 1e-16;
}

std::string gnuplot_script(const std::vector<LogLogPlot>& plots) {
  std::ostringstream script;
  script.precision(17);
  // Data as named blocks, each series sorted as given (callers sort by x); its zeros in a
  // block of their own, at the floor.
  for (std::size_t p = 0; p < plots.size(); ++p) {
    const double floor = zero_floor(plots[p]);
    for (std::size_t s = 0; s < plots[p].series.size(); ++s) {
      const std::vector<PlotPoint>& points = plots[p].series[s].points;
      script << "$p" << p << "_" << s << " << EOD\n";
      for (const PlotPoint& point : points) {
        if (!drawable(point) || point.y == 0.0) continue;
        script << point.x << " " << point.y;
        if (plots[p].x_error_bars) script << " " << point.x_low << " " << point.x_high;
        script << "\n";
      }
      script << "EOD\n";
      if (std::none_of(points.begin(), points.end(),
                       [](const PlotPoint& q) { return drawable(q) && q.y == 0.0; })) {
        continue;
      }
      script << "$p" << p << "_" << s << "_zero << EOD\n";
      for (const PlotPoint& point : points) {
        if (drawable(point) && point.y == 0.0) script << point.x << " " << floor << "\n";
      }
      script << "EOD\n";
    }
  }
  script << "set logscale xy\nset format x '10^{%L}'\nset format y '10^{%L}'\n"
         << "set grid xtics ytics mxtics mytics lc rgb '#dddddd'\n"
         << "set key outside right top box\nset mxtics 10\nset mytics 10\n";
  for (std::size_t p = 0; p < plots.size(); ++p) {
    const std::string stem = plots[p].file_stem.string();
    script << "set terminal png size 1000,650 font ',11'\nset output "
           << gnuplot_quoted(stem + ".png") << "\n";
    plot_commands(script, plots[p], p);
    script << "set output\nset terminal svg size 1000,650 dynamic font 'sans,12'\nset output "
           << gnuplot_quoted(stem + ".svg") << "\n";
    plot_commands(script, plots[p], p);
    script << "set output\n";
  }
  return script.str();
}

std::string gnuplot_quoted(const std::string& text) {
  std::string out = "'";  // '' escapes a quote
  for (char c : text) {
    if (c == '\'')
      out += "''";
    else
      out += c;
  }
  return out + "'";
}

void run_gnuplot(const std::string& script, const std::filesystem::path& script_file,
                 const std::vector<std::filesystem::path>& pictures) {
  const std::filesystem::path log = script_file.string() + ".log";
  write_text_file(script_file, script);
  const std::string command =
      "gnuplot " + shell_quoted(script_file.string()) + " >" + shell_quoted(log.string()) + " 2>&1";
  const int status = std::system(command.c_str());
  std::string first_line;
  {
    std::ifstream in(log);
    for (std::string line; first_line.empty() && std::getline(in, line);) first_line = line;
  }
  std::error_code ignored;
  std::filesystem::remove(script_file, ignored);
  std::filesystem::remove(log, ignored);
  if (status != 0) {
    throw InputError("gnuplot failed" + (first_line.empty() ? " (status " + std::to_string(status) +
                                                                  "; is gnuplot installed?)"
                                                            : ": " + first_line));
  }
  check_pictures(pictures);
}

void draw_plots(const std::vector<LogLogPlot>& plots, const std::filesystem::path& script_file) {
  std::vector<std::filesystem::path> pictures;
  for (const LogLogPlot& plot : plots) {
    pictures.push_back(plot.file_stem.string() + ".png");
    pictures.push_back(plot.file_stem.string() + ".svg");
  }
  run_gnuplot(gnuplot_script(plots), script_file, pictures);
}

}  // namespace tumble::app
