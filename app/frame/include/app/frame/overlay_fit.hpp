#pragma once
/// @file How big an overlay panel is and how it is made to fit its frame (or compare tile).
///
/// Rule: a panel covers at most kOverlayCoverageBudget of the frame's pixels (the bound checked
/// by the tests is 20 %; the estimate is within a few pixels of ImGui's layout). When it would
/// be larger, its droppable lines go first (last first), then its plots shrink to twice the
/// text height, then the plots are dropped, last first. Other lines always stay.

#include <cstddef>

#include "render/draw_list.hpp"

namespace tumble::app {

/// Share of a frame's pixels an overlay panel may cover.
inline constexpr double kOverlayCoverageBudget = 0.18;

/// Pixel size of a panel laid out by the renderer's ImGui pass.
struct OverlayPanelSize {
  float width = 0.0f;
  float height = 0.0f;
};

/// The size `panel` takes at its font_px, as wide as its longest text (title, lines, plot
/// captions with their value); a compact panel's, as wide as its longest line.
OverlayPanelSize overlay_panel_size(const render::OverlayPanel& panel);

/// Applies the rule above for a `width` x `height` frame, with `coverage` the share of its
/// pixels the panel may cover; panel.lines from `first_droppable` on may be dropped. Sets
/// panel.width_px (at most the frame's width less the panel's margins).
void fit_overlay_panel(render::OverlayPanel& panel, std::size_t first_droppable, int width,
                       int height, double coverage = kOverlayCoverageBudget);

}  // namespace tumble::app
