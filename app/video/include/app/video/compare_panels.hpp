#pragma once
/// @file The overlay panels of `tumble compare`: each grid tile's panel fitted to its tile, the
/// drift plots of all tiles on one scale, and the overlay layout's legend fitted to the frame.

#include <string>
#include <vector>

#include "render/draw_list.hpp"

namespace tumble::app {

/// Share of a tile's pixels its panel may cover (estimated; the tests measure at most 15 %).
inline constexpr double kTileCoverageBudget = 0.14;

/// What a tile's panel says, each number as printed.
struct TileText {
  std::string integrator;  ///< "rk4"
  std::string dt;          ///< the run's step in seconds: "0.001"
  std::string time;        ///< the time shown in seconds: "12.345"
  std::string blow_up;     ///< when the run blew up, in seconds; empty when it did not
};

/// Makes a run's overlay panel (as the FrameBuilder laid it out for the tile's size) say
/// `text` within a `tile_width` x `tile_height` tile, every word whole, its text never under
/// render::kMinFontPx, covering at most kTileCoverageBudget of the tile:
/// - the full panel when it fits: "integrator, dt = H s" as its title (its text made smaller
///   until the title fits the tile's width), the time and the blow-up as its lines, and its
///   drift plots as the overlay's coverage rule (app/frame/overlay_fit.hpp) allows;
/// - otherwise a compact corner label (render::OverlayPanel::compact: no title bar, tight
///   padding), the integrator on a line of its own, "dt H s, t = T s" below it (split in two
///   when it does not fit) and the blow-up, without plots. A 240x134 tile (2x2 grid in a
///   480x270 GIF) gets this label; with `compact`, any tile does (so that every tile of a
///   grid shows the same form).
void fit_tile_panel(render::OverlayPanel& panel, const TileText& text, int tile_width,
                    int tile_height, bool compact = false);

/// Fits every list's first panel to its tile with texts[i], all in one form: compact labels
/// for all when any tile needs one, and as many drift plots in each as every tile keeps.
void fit_tile_panels(std::vector<render::DrawList>& lists, const std::vector<TileText>& texts,
                     int tile_width, int tile_height);

/// Puts plot k of every list's first panel on one vertical scale: the common range of their
/// values (of |value| on log axes), so that 1e-11 and 9e-2 do not look alike.
void share_plot_scales(std::vector<render::DrawList>& lists);

/// Fits the legend panel (title and one line per run, none dropped) to a `width` x `height`
/// frame: text at the frame's size and `font_scale`, made smaller (not under
/// render::kMinFontPx) until the longest line fits inside the frame.
void fit_legend_panel(render::OverlayPanel& legend, int width, int height, double font_scale);

}  // namespace tumble::app
