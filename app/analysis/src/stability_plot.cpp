// The stability heat map: gnuplot boxes coloured per outcome, one panel per case.
#include "app/analysis/stability_plot.hpp"

#include "app/analysis/gnuplot.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "app/support/file_write.hpp"
#include "base/errors.hpp"

namespace tumble::app {
namespace {

/// Cell colour per outcome, 0xRRGGBB.
long colour(StabilityOutcome outcome) {
  switch (outcome) {
    case StabilityOutcome::kStable:
      return 0x2ca02c;
    case StabilityOutcome::kDrifting:
      return 0xffbf00;
    case StabilityOutcome::kDamped:
      return 0x4a90d9;
    case StabilityOutcome::kWrong:
      return 0x9467bd;
    case StabilityOutcome::kBlewUp:
      return 0xd62728;
    case StabilityOutcome::kUnchecked:
      return 0xa0d0a0;
    case StabilityOutcome::kSkipped:
      return 0xdddddd;
  }
  return 0xffffff;
}

constexpr StabilityOutcome kLegend[] = {StabilityOutcome::kStable, StabilityOutcome::kDrifting,
                                        StabilityOutcome::kDamped, StabilityOutcome::kWrong,
                                        StabilityOutcome::kBlewUp, StabilityOutcome::kUnchecked,
                                        StabilityOutcome::kSkipped};

std::string hex(long value) {
  char buffer[16];
  std::snprintf(buffer, sizeof buffer, "#%06lx", value);
  return buffer;
}

/// The multiplot body (terminal and output set by the caller).
std::string panels_script(const std::vector<HeatMapPanel>& panels, std::size_t layout_rows,
                          std::size_t layout_columns) {
  std::ostringstream s;
  s << "set multiplot layout " << layout_rows << "," << layout_columns << "\n";
  for (std::size_t p = 0; p < panels.size(); ++p) {
    const HeatMapPanel& panel = panels[p];
    const std::size_t rows = panel.rows.size(), columns = panel.columns.size();
    s << "set title " << gnuplot_quoted(panel.title) << "\n";
    s << "set xlabel " << gnuplot_quoted(panel.x_label) << "\n";
    s << "set xrange [-0.5:" << static_cast<double>(columns) - 0.5 << "]\n";
    s << "set yrange [-0.5:" << static_cast<double>(rows) - 0.5 << "]\n";
    s << "set xtics (";
    for (std::size_t c = 0; c < columns; ++c) {
      s << (c ? ", " : "") << gnuplot_quoted(panel.columns[c]) << " " << c;
    }
    s << ")\nset ytics (";
    for (std::size_t r = 0; r < rows; ++r) {
      s << (r ? ", " : "") << gnuplot_quoted(panel.rows[r]) << " " << rows - 1 - r;
    }
    s << ")\n";
    s << "plot $panel" << p << " using 1:2:(0.5):(0.5):3 with boxxy lc rgb variable notitle, "
      << "$panel" << p << " using 1:2:4 with labels font \",8\" notitle";
    for (const StabilityOutcome outcome : kLegend) {
      s << ", NaN with boxes lc rgb " << gnuplot_quoted(hex(colour(outcome))) << " title "
        << gnuplot_quoted(outcome_name(outcome));
    }
    s << "\n";
  }
  s << "unset multiplot\n";
  return s.str();
}

}  // namespace

std::string heat_map_script(const std::vector<HeatMapPanel>& panels,
                            const std::filesystem::path& png, const std::filesystem::path& svg) {
  std::ostringstream s;
  // Data: one block per panel, "column row colour label" per cell.
  for (std::size_t p = 0; p < panels.size(); ++p) {
    const HeatMapPanel& panel = panels[p];
    s << "$panel" << p << " << EOD\n";
    for (std::size_t r = 0; r < panel.rows.size(); ++r) {
      for (std::size_t c = 0; c < panel.columns.size(); ++c) {
        const StabilityOutcome outcome = panel.cells[r][c];
        // Data fields take double quotes (gnuplot's command quoting does not apply here).
        s << c << " " << panel.rows.size() - 1 - r << " " << colour(outcome) << " \""
          << outcome_name(outcome) << "\"\n";
      }
    }
    s << "EOD\n";
  }
  // Style shared by every panel.
  const std::size_t layout_columns = panels.size() > 1 ? 2 : 1;
  const std::size_t layout_rows = std::max<std::size_t>(1, (panels.size() + 1) / layout_columns);
  std::size_t tallest = 1;
  for (const HeatMapPanel& panel : panels) tallest = std::max(tallest, panel.rows.size());
  const std::size_t width = 900 * layout_columns;
  const std::size_t height = layout_rows * (120 + 28 * tallest);
  s << "set style fill solid 1.0 border rgb \"white\"\n"
    << "set key outside right top\nset tics nomirror\n";
  // The same plot twice: PNG, then SVG.
  s << "set terminal pngcairo size " << width << "," << height << " font \",9\"\n"
    << "set output " << gnuplot_quoted(png.string()) << "\n"
    << panels_script(panels, layout_rows, layout_columns) << "set output\n";
  s << "set terminal svg size " << width << "," << height << " font \",9\"\n"
    << "set output " << gnuplot_quoted(svg.string()) << "\n"
    << panels_script(panels, layout_rows, layout_columns) << "set output\n";
  return s.str();
}

void draw_heat_map(const std::vector<HeatMapPanel>& panels, const std::filesystem::path& png,
                   const std::filesystem::path& svg) {
  try {
    run_gnuplot(heat_map_script(panels, png, svg), png.parent_path() / ".stability.gp", {png, svg});
  } catch (const WriteError&) {
    throw;  // names its file
  } catch (const std::runtime_error& error) {
    throw tumble::InputError(std::string("the heat map: ") + error.what());
  }
}

}  // namespace tumble::app
