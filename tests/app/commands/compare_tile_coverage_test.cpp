// The panels of `tumble compare`'s grid tiles, measured in pixels: a tile of the T-handle demo
// is rendered with and without its overlay (panel and labels), at the tile sizes of a 2x2 grid
// in a 480x270 GIF (240x134) and a 3x3 grid in 1280x720 (426x240). The pixels the overlay
// changes are at most 15 % of the tile, the body stays in view, the text is never under the
// minimum size, and every line of text is whole: its inked width, measured in the image, is
// that of all its characters and ends inside the panel (ImGui would clip it at the panel's
// padding).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "../frame/frame_scene_setup.hpp"
#include "app/commands/compare_command.hpp"
#include "app/frame/overlay_fit.hpp"
#include "app/video/compare_panels.hpp"
#include "render/overlay_layout.hpp"

namespace tumble::app {
namespace {

std::string demo_scene() {
  std::ifstream in(std::string(TUMBLE_SOURCE_DIR) + "/assets/scenes/t_handle_flip.json");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

bool differs(const tumble::Image& a, const tumble::Image& b, int x, int y) {
  return !std::equal(a.pixel(x, y), a.pixel(x, y) + 3, b.pixel(x, y));
}

/// One tile at t = 2 s: its fitted panel and the tile rendered with the overlay, without it,
/// and without the bodies and their items (the background alone).
struct TileShot {
  render::OverlayPanel panel;
  tumble::Image with;
  tumble::Image without;
  tumble::Image background;

  TileShot(int width, int height, const TileText& text) {
    const testing::FrameSceneSetup setup(demo_scene(), width, height);
    engine::Simulation simulation = setup.simulation();
    FrameBuilder builder = setup.builder();
    const double frame_dt = setup.settings.time_scale / setup.settings.fps;
    for (double t = 0.0; t <= 2.0 + 1e-9; t += frame_dt) {
      while (simulation.time() + 1e-4 <= t) simulation.step();
      builder.observe(simulation);
    }
    render::DrawList list = builder.build(simulation);
    EXPECT_EQ(list.panels.size(), 1u);
    fit_tile_panel(list.panels.front(), text, width, height);
    panel = list.panels.front();
    render::Renderer& renderer = setup.renderer();
    with = renderer.render(list);
    list.panels.clear();
    list.labels.clear();
    without = renderer.render(list);
    list.meshes.clear();
    list.arrows.clear();
    list.polylines.clear();
    list.points.clear();
    background = renderer.render(list);
  }

  double coverage() const {
    int changed = 0;
    for (int y = 0; y < with.height; ++y) {
      for (int x = 0; x < with.width; ++x) changed += differs(with, without, x, y) ? 1 : 0;
    }
    return static_cast<double>(changed) / (with.width * with.height);
  }

  /// Share of the body's pixels (those the bodies and their items change) still as they are
  /// without the overlay; and the body's share of the tile.
  std::pair<double, double> body_visible() const {
    int body = 0;
    int seen = 0;
    for (int y = 0; y < with.height; ++y) {
      for (int x = 0; x < with.width; ++x) {
        if (!differs(without, background, x, y)) continue;
        ++body;
        seen += differs(with, without, x, y) ? 0 : 1;
      }
    }
    return {static_cast<double>(seen) / std::max(body, 1),
            static_cast<double>(body) / (with.width * with.height)};
  }

  /// First and last columns of text ink (near-white pixels the overlay put there) in rows
  /// [top, bottom) of the panel; {-1, -1} when there is none.
  std::pair<int, int> ink_columns(int top, int bottom) const {
    int first = -1;
    int last = -1;
    for (int y = std::max(top, 0); y < std::min(bottom, with.height); ++y) {
      for (int x = 0; x < with.width; ++x) {
        const std::uint8_t* p = with.pixel(x, y);
        if (p[0] < 200 || p[1] < 200 || p[2] < 200 || !differs(with, without, x, y)) continue;
        first = first < 0 ? x : std::min(first, x);
        last = std::max(last, x);
      }
    }
    return {first, last};
  }
};

/// Checks that `text`, drawn at the panel's size in rows [top, top + font_px), is whole.
void expect_whole(const TileShot& shot, const std::string& text, float top, float padding) {
  const render::OverlayPanel& panel = shot.panel;
  const float px = panel.font_px;
  const auto [first, last] =
      shot.ink_columns(static_cast<int>(top), static_cast<int>(top + px + 0.5f));
  ASSERT_GE(first, 0) << "no ink for '" << text << "'";
  const float inked = static_cast<float>(last - first + 1);
  const float full = render::overlay_text_width(text.size(), px);
  const float glyph = render::overlay_text_width(1, px);
  // All its characters are there (the last glyph's ink may stop short of its advance) ...
  EXPECT_GE(inked, full - glyph) << "'" << text << "' inked " << inked << " of " << full << " px";
  EXPECT_LE(inked, full) << "'" << text << "' is wider than estimated";
  // ... and none was clipped: the ink ends inside the panel, short of its padding.
  const float right = panel.position_px.x() + panel.width_px;
  EXPECT_LT(static_cast<float>(last), right - 0.5f * padding) << "'" << text << "'";
}

struct TileCase {
  const char* name;
  int panels;  ///< of the grid ...
  int width;   ///< ... in a frame this size
  int height;
  TileText text;
};

class CompareTile : public ::testing::TestWithParam<TileCase> {};

TEST_P(CompareTile, OverlayCoversAtMostFifteenPercentWithWholeText) {
  const TileCase& c = GetParam();
  const GridLayout grid = grid_layout(static_cast<std::size_t>(c.panels), c.width, c.height);
  const TileShot shot(grid.tile_width, grid.tile_height, c.text);
  const render::OverlayPanel& panel = shot.panel;
  const double coverage = shot.coverage();
  const auto [visible, body] = shot.body_visible();
  std::printf(
      "[ tile     ] %s %dx%d: %s, font %.0f px, %zu lines, %zu plots, coverage %.1f %%, "
      "body %.1f %% of the tile, %.1f %% of it visible\n",
      c.name, grid.tile_width, grid.tile_height, panel.compact ? "compact" : "full",
      static_cast<double>(panel.font_px), panel.lines.size(), panel.plots.size(), 100.0 * coverage,
      100.0 * body, 100.0 * visible);
  EXPECT_LE(coverage, 0.15);
  EXPECT_GT(coverage, 0.01);  // it is drawn at all
  EXPECT_GE(panel.font_px, render::kMinFontPx);
  EXPECT_GT(body, 0.05);
  EXPECT_GE(visible, 0.85);
  // The panel lies inside the tile.
  const OverlayPanelSize size = overlay_panel_size(panel);
  EXPECT_GE(panel.position_px.minCoeff(), 0.0f);
  EXPECT_LE(panel.position_px.x() + panel.width_px, static_cast<float>(grid.tile_width));
  EXPECT_LE(panel.position_px.y() + size.height, static_cast<float>(grid.tile_height));

  const float px = panel.font_px;
  if (panel.compact) {
    // The integrator has a line of its own; every line is whole.
    ASSERT_FALSE(panel.lines.empty());
    EXPECT_EQ(panel.lines[0], c.text.integrator);
    const float padding = render::compact_panel_padding(px);
    const float gap = render::compact_panel_spacing(px);
    for (std::size_t i = 0; i < panel.lines.size(); ++i) {
      expect_whole(shot, panel.lines[i],
                   panel.position_px.y() + padding + static_cast<float>(i) * (px + gap), padding);
    }
  } else {
    // The title bar holds "integrator, dt = H s", whole.
    EXPECT_EQ(panel.title, c.text.integrator + ", dt = " + c.text.dt + " s");
    const float u = px / render::kDefaultFontPx;
    expect_whole(shot, panel.title, panel.position_px.y() + 3.0f * u, 8.0f * u);
  }
}

const TileText kLongest{"semi-implicit-euler", "0.001", "12.345", ""};
const TileText kBlownUp{"explicit-euler", "0.002", "2.498", "2.5"};

INSTANTIATE_TEST_SUITE_P(
    Grids, CompareTile,
    ::testing::Values(TileCase{"2x2_in_480x270", 4, 480, 270, kLongest},
                      TileCase{"2x2_in_480x270_blown_up", 4, 480, 270, kBlownUp},
                      TileCase{"3x3_in_1280x720", 9, 1280, 720, kLongest},
                      TileCase{"3x3_in_1280x720_blown_up", 9, 1280, 720, kBlownUp}),
    [](const ::testing::TestParamInfo<TileCase>& param) { return std::string(param.param.name); });

}  // namespace
}  // namespace tumble::app
