// gnuplot's pictures checked whole: gnuplot exits 0 when its output is cut short (a full disk),
// so a PNG must end with its IEND chunk and an SVG with its closing tag.
#include "app/analysis/gnuplot.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>

#include "app/analysis/bench_report.hpp"
#include "app/support/file_write.hpp"
#include "engine/dynamics/integrators.hpp"
#include "support/run_command.hpp"

namespace tumble::app {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const std::string kPngSignature("\x89PNG\r\n\x1a\n", 8);
const std::string kIend("\0\0\0\0IEND\xae\x42\x60\x82", 12);

class CheckPictures : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = testing::fresh_directory("CheckPictures"); }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path file(const std::string& name, const std::string& bytes) const {
    std::ofstream(dir_ / name, std::ios::binary) << bytes;
    return dir_ / name;
  }
  /// The message of the WriteError check_pictures throws for `pictures` (empty: none thrown).
  static std::string error_of(const std::vector<fs::path>& pictures) {
    try {
      check_pictures(pictures);
    } catch (const WriteError& error) {
      return error.what();
    }
    return {};
  }
  fs::path dir_;
};

TEST_F(CheckPictures, WholePngAndSvgPass) {
  const fs::path png = file("a.png", kPngSignature + std::string(5000, 'p') + kIend);
  const fs::path svg = file("a.svg", "<svg>\n<g>\n</g>\n</svg>\n\n");
  EXPECT_EQ(error_of({png, svg}), "");
}

TEST_F(CheckPictures, ACutPngIsNamed) {
  const fs::path svg = file("a.svg", "<svg>\n</svg>\n");
  const fs::path png = file("a.png", kPngSignature + std::string(4088, 'p'));
  EXPECT_EQ(error_of({svg, png}), "cannot write '" + png.string() +
                                      "': gnuplot stopped after 4096 bytes, the picture is "
                                      "incomplete (is the disk full?)");
}

TEST_F(CheckPictures, ACutOrMissingSvgIsNamed) {
  const fs::path svg = file("a.svg", "<svg>\n<g>\n<path d='M 1 2 L");
  EXPECT_THAT(error_of({svg}), HasSubstr("cannot write '" + svg.string() + "': gnuplot stopped"));
  EXPECT_EQ(error_of({dir_ / "b.svg"}), "cannot write '" + (dir_ / "b.svg").string() +
                                            "': gnuplot wrote no picture (is the disk full?)");
}

// bench's plots: the style of each integrator fixed by its name, zero errors at a floor marker.

/// A run of `integrator` on `scene` with final orientation error `error` (every measure the same).
void add_run(BenchOutcome& outcome, std::size_t scene, const std::string& integrator, double dt,
             double error, double seconds) {
  BenchCase c;
  c.scene = scene;
  c.integrator = integrator;
  c.dt = dt;
  outcome.cases.push_back(c);
  CaseResult r;
  r.errors.orientation_final = r.errors.orientation_max = error;
  r.median_seconds = seconds;
  r.min_seconds = 0.9 * seconds;
  r.max_seconds = 1.2 * seconds;
  r.counts.accepted = static_cast<std::size_t>(1.0 / dt);
  r.counts.evaluations = 4 * r.counts.accepted;
  outcome.results.push_back(r);
}

/// The style text (" linecolor rgb '...' pointtype N") of the series titled `title` in each plot
/// command line of `script` that draws it as a line (not as floor markers).
std::vector<std::string> styles_of(const std::string& script, const std::string& title) {
  std::vector<std::string> styles;
  std::istringstream in(script);
  for (std::string line; std::getline(in, line);) {
    const auto at = line.find(" title '" + title + "'");
    const auto colour = line.find(" linecolor rgb ");
    if (at == std::string::npos || colour == std::string::npos || colour > at) continue;
    if (line.find("_zero using") != std::string::npos) continue;  // a floor marker
    styles.push_back(line.substr(colour, at - colour));
  }
  return styles;
}

BenchOutcome two_scene_outcome() {
  BenchOutcome outcome;
  outcome.scenes.resize(2);
  outcome.scenes[0].label = outcome.scenes[0].name = "a";
  outcome.scenes[1].label = outcome.scenes[1].name = "b";
  // Scene a: rk4 first; scene b: dopri first and no rk4, so list positions differ.
  add_run(outcome, 0, "rk4", 0.01, 1e-6, 0.01);
  add_run(outcome, 0, "rk4", 0.005, 6e-8, 0.02);
  add_run(outcome, 0, "dopri", 0.01, 1e-7, 0.005);
  add_run(outcome, 1, "dopri", 0.01, 1e-5, 0.005);
  add_run(outcome, 1, "splitting", 0.01, 1e-3, 0.002);
  add_run(outcome, 1, "free-rotor", 0.01, 0.0, 0.004);  // exact: an error of exactly 0
  add_run(outcome, 1, "free-rotor", 0.005, 2e-16, 0.008);
  return outcome;
}

TEST(BenchPlots, EachIntegratorHasOneStyleInEveryPlot) {
  const BenchOutcome outcome = two_scene_outcome();
  const std::vector<LogLogPlot> plots = bench_plots(outcome, "out");
  // Two plots (run time, evaluations) per scene and measure.
  ASSERT_EQ(plots.size(), 2 * 2 * plotted_measures().size());
  const std::string script = gnuplot_script(plots);
  for (const char* name : {"rk4", "dopri", "splitting"}) {
    const std::vector<std::string> styles = styles_of(script, name);
    ASSERT_FALSE(styles.empty()) << name;
    for (const std::string& style : styles) EXPECT_EQ(style, styles.front()) << name;
    const PlotStyle expected = integrator_style(name);
    EXPECT_EQ(styles.front(), " linecolor rgb '" + expected.colour + "' pointtype " +
                                  std::to_string(expected.point_type));
  }
  EXPECT_NE(styles_of(script, "rk4").front(), styles_of(script, "dopri").front());
  // Every catalog integrator its own colour and marker pair.
  std::set<std::pair<std::string, int>> seen;
  for (const auto& info : engine::integrator_catalog()) {
    const PlotStyle style = integrator_style(info.name);
    EXPECT_TRUE(seen.insert({style.colour, style.point_type}).second) << info.name;
  }
  // Run time with the min-max bar; evaluations without.
  EXPECT_TRUE(plots[0].x_error_bars);
  EXPECT_FALSE(plots[1].x_error_bars);
  EXPECT_EQ(plots[1].file_stem, std::filesystem::path("out") / "a_orientation_final_evaluations");
  ASSERT_EQ(plots[1].series.size(), 2u);
  EXPECT_EQ(plots[1].series[0].points[0].x, 400.0);  // 4 evaluations x 100 steps
  EXPECT_THAT(script, HasSubstr("using 1:2:3:4 with xerrorlines"));
}

TEST(BenchPlots, AZeroErrorIsDrawnAtTheFloorAndNamed) {
  const BenchOutcome outcome = two_scene_outcome();
  const std::vector<LogLogPlot> plots = bench_plots(outcome, "out");
  const LogLogPlot& b = plots[2 * plotted_measures().size()];  // scene b, final orientation
  ASSERT_EQ(b.file_stem, std::filesystem::path("out") / "b_orientation_final");
  // The smallest non-zero error is 2e-16: the floor a decade below its decade.
  EXPECT_DOUBLE_EQ(zero_floor(b), 1e-17);
  const std::string script = gnuplot_script({b});
  // free-rotor is series 2 of the plot; its zero sits in a block of its own, at the floor.
  std::ostringstream floor_line;
  floor_line.precision(17);
  floor_line << "$p0_2_zero << EOD\n" << 0.004 << " " << zero_floor(b) << "\nEOD\n";
  EXPECT_THAT(script, HasSubstr(floor_line.str()));
  // The free-rotor's other run is drawn as usual, so its zero marker goes without a title.
  EXPECT_THAT(script, HasSubstr("pointtype 10 pointsize 1.6 notitle"));
  EXPECT_THAT(script, HasSubstr("open triangles:\\nerror exactly 0,\\ndrawn at 1e-17"));
  EXPECT_THAT(script, HasSubstr("$p0_2_zero using 1:2 with points linecolor rgb '" +
                                integrator_style("free-rotor").colour + "' pointtype 10"));
  // A plot with no zero has no note.
  EXPECT_THAT(gnuplot_script({plots[0]}), ::testing::Not(HasSubstr("exactly 0")));
}

}  // namespace
}  // namespace tumble::app
