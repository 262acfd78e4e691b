// The panels of `tumble compare`: tiles' panels fitted to their tiles with their titles whole,
// drift plots on one scale, and the legend inside the frame.
#include "app/video/compare_panels.hpp"

#include <gtest/gtest.h>

#include "app/frame/overlay_fit.hpp"
#include "render/overlay_layout.hpp"

namespace tumble::app {
namespace {

/// A tile's panel as the FrameBuilder lays it out for the tile, before fitting.
render::OverlayPanel run_panel(int tile_width, int tile_height, std::vector<float> drift) {
  render::OverlayPanel panel;
  panel.font_px = render::overlay_font_px(tile_width, tile_height);
  render::Plot energy{"energy drift", drift, {}, {}, 40.0f, render::PlotAxis::kLog};
  render::Plot momentum{"|L| drift", drift, {}, {}, 40.0f, render::PlotAxis::kLog};
  panel.plots = {energy, momentum};
  return panel;
}

class TilePanel : public ::testing::TestWithParam<std::pair<int, int>> {};

TEST_P(TilePanel, KeepsItsWordsWholeAndCoversAtMostItsShareOfTheTile) {
  const auto [width, height] = GetParam();
  render::OverlayPanel panel = run_panel(width, height, {0.0f, 1e-6f, 2e-6f});
  const TileText text{"explicit-euler", "0.001", "12.345", ""};
  fit_tile_panel(panel, text, width, height);
  EXPECT_GE(panel.font_px, render::kMinFontPx);
  // Every text fits inside the panel, and the panel inside the tile.
  const float margin = panel.position_px.x();
  std::vector<std::string> texts = panel.lines;
  if (!panel.compact) texts.push_back(panel.title);
  for (const std::string& line : texts) {
    EXPECT_LE(render::overlay_text_width(line.size(), panel.font_px), panel.width_px) << line;
  }
  EXPECT_LE(panel.position_px.x() + panel.width_px, static_cast<float>(width) - margin);
  const OverlayPanelSize size = overlay_panel_size(panel);
  EXPECT_LE(panel.position_px.y() + size.height, static_cast<float>(height) - margin);
  EXPECT_LE(size.width * size.height, kTileCoverageBudget * width * height);
  if (width >= 320) {
    // The full panel: the title bar names the run, the time is never dropped; a plot needs a
    // 426x240 tile (3x3 grid in 1280x720), both plots a 640x360 one.
    EXPECT_FALSE(panel.compact);
    EXPECT_EQ(panel.title, "explicit-euler, dt = 0.001 s");
    EXPECT_EQ(panel.lines, std::vector<std::string>{"t = 12.345 s"});
    EXPECT_EQ(panel.plots.size(), width >= 640 ? 2u : width >= 426 ? 1u : 0u);
  } else {
    // A 240x134 tile (2x2 grid in a 480x270 GIF): the compact corner label, the integrator on
    // a line of its own (the full panel would take ~21 %).
    EXPECT_TRUE(panel.compact);
    EXPECT_TRUE(panel.plots.empty());
    EXPECT_EQ(panel.lines,
              (std::vector<std::string>{"explicit-euler", "dt 0.001 s, t = 12.345 s"}));
  }
}

TEST(TilePanel, SplitsTheStepAndTimeWhenTheyDoNotFitSideBySide) {
  // A 4x4 grid in 480x270: 120x66 tiles.
  render::OverlayPanel panel = run_panel(120, 66, {0.0f, 1e-6f});
  fit_tile_panel(panel, {"semi-implicit-euler", "0.0001", "123.456", "99.5"}, 120, 66);
  EXPECT_TRUE(panel.compact);
  EXPECT_EQ(panel.font_px, render::kMinFontPx);
  EXPECT_EQ(panel.lines, (std::vector<std::string>{"semi-implicit-euler", "dt 0.0001 s",
                                                   "t = 123.456 s", "blew up at t = 99.5 s"}));
  for (const std::string& line : panel.lines) {
    EXPECT_LE(render::overlay_text_width(line.size(), panel.font_px), panel.width_px) << line;
  }
}

// Tiles of a 2x2 grid in 480x270 (GIF), 640x360, 1280x720 and 3840x2160 frames, and of a 3x3
// grid in 1280x720.
INSTANTIATE_TEST_SUITE_P(TileSizes, TilePanel,
                         ::testing::Values(std::pair{240, 134}, std::pair{320, 180},
                                           std::pair{426, 240}, std::pair{640, 360},
                                           std::pair{1920, 1080}));

TEST(ComparePanels, EveryTileOfAGridTakesTheSameForm) {
  const std::vector<TileText> texts = {{"rk4", "0.001", "1.000", ""},
                                       {"semi-implicit-euler", "0.001", "1.000", ""},
                                       {"explicit-euler", "0.001", "1.000", ""}};
  // 240x134: "rk4"'s full panel alone would fit (13.6 %), the longer names' would not, so
  // every tile gets the compact label. 426x240: full panels, each with as many plots as the
  // one with the longest title keeps.
  for (const auto& [width, height] : {std::pair{240, 134}, std::pair{426, 240}}) {
    render::OverlayPanel alone = run_panel(width, height, {0.0f, 1e-6f});
    fit_tile_panel(alone, texts[0], width, height);
    std::vector<render::DrawList> lists(texts.size());
    for (render::DrawList& list : lists) list.panels.push_back(run_panel(width, height, {0.0f}));
    fit_tile_panels(lists, texts, width, height);
    for (std::size_t i = 0; i < lists.size(); ++i) {
      const render::OverlayPanel& panel = lists[i].panels.front();
      EXPECT_EQ(panel.compact, width == 240) << width << " " << texts[i].integrator;
      EXPECT_EQ(panel.plots.size(), lists[1].panels.front().plots.size());
      EXPECT_LE(panel.position_px.x() + panel.width_px, static_cast<float>(width));
    }
    EXPECT_FALSE(alone.compact);
    if (width == 426) {
      EXPECT_EQ(alone.plots.size(), 1u);
    }
  }
}

TEST(ComparePanels, EveryTileShowsItsDriftOnTheSameScale) {
  std::vector<render::DrawList> lists(3);
  const std::vector<std::vector<float>> drifts = {
      {0.0f, 1e-11f, -3e-11f}, {0.0f, 0.02f, 0.09f}, {0.0f, -4e-5f, 2e-5f}};
  for (std::size_t i = 0; i < lists.size(); ++i) {
    lists[i].panels.push_back(run_panel(640, 360, drifts[i]));
  }
  share_plot_scales(lists);
  for (const render::DrawList& list : lists) {
    for (const render::Plot& plot : list.panels[0].plots) {
      ASSERT_TRUE(plot.min && plot.max);
      // |value| range over all runs, the zero floored at log_floor.
      EXPECT_EQ(*plot.min, plot.log_floor);
      EXPECT_FLOAT_EQ(*plot.max, 0.09f);
    }
  }
}

TEST(ComparePanels, LegendLinesStayWholeInsideTheFrame) {
  for (const auto& [width, height] : {std::pair{480, 270}, std::pair{1280, 720}}) {
    render::OverlayPanel legend;
    legend.title = "dzhanibekov";
    legend.lines = {"t = 3.000 s", "orange: explicit-euler, dt = 0.001 s (blew up at t = 2.5 s)",
                    "blue: rk4, dt = 0.001 s", "grey ghost: reference-adaptive (reference)"};
    fit_legend_panel(legend, width, height, 1.0);
    EXPECT_GE(legend.font_px, render::kMinFontPx);
    EXPECT_LE(legend.position_px.x() + legend.width_px, static_cast<float>(width));
    for (const std::string& line : legend.lines) {
      EXPECT_LE(render::overlay_text_width(line.size(), legend.font_px), legend.width_px) << line;
    }
  }
}

}  // namespace
}  // namespace tumble::app
