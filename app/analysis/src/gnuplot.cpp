#include "app/analysis/gnuplot.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "app/support/file_write.hpp"
#include "tumble/errors.hpp"

namespace tumble::app {
namespace {

std::string quoted(const std::string& text) {
  return gnuplot_quoted(text);
}

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

/// The drawing commands of one plot (after `set terminal` and `set output`).
void plot_commands(std::ostream& script, const LogLogPlot& plot, std::size_t index) {
  script << "set title " << quoted(plot.title) << " noenhanced\n"
         << "set xlabel " << quoted(plot.x_label) << " noenhanced\n"
         << "set ylabel " << quoted(plot.y_label) << " noenhanced\n";
  std::vector<std::size_t> drawn;
  for (std::size_t s = 0; s < plot.series.size(); ++s) {
    std::size_t count = 0;
    for (const auto& [x, y] : plot.series[s].points) count += x > 0.0 && y > 0.0;
    if (count > 0) drawn.push_back(s);
  }
  if (drawn.empty()) {
    // Nothing positive to draw on log axes: an empty frame that says so.
    script << "set label 1 'no positive values to plot' at graph 0.5, 0.5 center\n"
           << "plot [1e-6:1] [1e-16:1] 1/0 notitle\nunset label 1\n";
    return;
  }
  script << "plot ";
  for (std::size_t j = 0; j < drawn.size(); ++j) {
    script << (j ? ", \\\n     " : "") << "$p" << index << "_" << drawn[j]
           << " using 1:2 with linespoints pointtype " << (j % 13 + 1) << " title "
           << quoted(plot.series[drawn[j]].title) << " noenhanced";
  }
  script << "\n";
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

std::string gnuplot_script(const std::vector<LogLogPlot>& plots) {
  std::ostringstream script;
  script.precision(17);
  // Data as named blocks, each series sorted as given (callers sort by run time).
  for (std::size_t p = 0; p < plots.size(); ++p) {
    for (std::size_t s = 0; s < plots[p].series.size(); ++s) {
      script << "$p" << p << "_" << s << " << EOD\n";
      for (const auto& [x, y] : plots[p].series[s].points) {
        if (x > 0.0 && y > 0.0) script << x << " " << y << "\n";
      }
      script << "EOD\n";
    }
  }
  script << "set logscale xy\nset format x '10^{%L}'\nset format y '10^{%L}'\n"
         << "set grid xtics ytics mxtics mytics lc rgb '#dddddd'\n"
         << "set key outside right top box\nset mxtics 10\nset mytics 10\n";
  for (std::size_t p = 0; p < plots.size(); ++p) {
    const std::string stem = plots[p].file_stem.string();
    script << "set terminal png size 1000,650 font ',11'\nset output " << quoted(stem + ".png")
           << "\n";
    plot_commands(script, plots[p], p);
    script << "set output\nset terminal svg size 1000,650 dynamic font 'sans,12'\nset output "
           << quoted(stem + ".svg") << "\n";
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
