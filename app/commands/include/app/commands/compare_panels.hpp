#pragma once
/// @file The overlay panels of `tumble compare`: each grid tile's panel fitted to its tile, the
/// drift plots of all tiles on one scale, and the overlay layout's legend fitted to the frame.

#include <string>
#include <vector>

#include "render/draw_list.hpp"

namespace tumble::app {

/// Makes a run's overlay panel (as the FrameBuilder laid it out for the tile's size) show
/// `title` and `lines` (none dropped) within a `tile_width` x `tile_height` tile: the text is
/// made smaller (not under render::kMinFontPx) until the title fits the tile's width, then the
/// panel follows the overlay's coverage rule (app/frame/overlay_fit.hpp) within the tile.
void fit_tile_panel(render::OverlayPanel& panel, std::string title, std::vector<std::string> lines,
                    int tile_width, int tile_height);

/// Puts plot k of every list's first panel on one vertical scale: the common range of their
/// values (of |value| on log axes), so that 1e-11 and 9e-2 do not look alike.
void share_plot_scales(std::vector<render::DrawList>& lists);

/// Fits the legend panel (title and one line per run, none dropped) to a `width` x `height`
/// frame: text at the frame's size and `font_scale`, made smaller (not under
/// render::kMinFontPx) until the longest line fits inside the frame.
void fit_legend_panel(render::OverlayPanel& legend, int width, int height, double font_scale);

}  // namespace tumble::app
