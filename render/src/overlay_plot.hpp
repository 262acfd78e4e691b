#pragma once
// A time-series plot with axes drawn into the current ImGui window with its draw list
// (ImGui::PlotLines has no axes): the name and current value on a caption line, tick labels in a
// gutter left of the curve, faint grid lines at the ticks, the curve decimated to a min/max pair
// per two pixel columns.

#include "render/draw_list.hpp"

namespace tumble::render::detail {

/// Draws `plot` at the window's cursor, as wide as the content region, with text of the current
/// font; advances the cursor past it.
void draw_plot(const Plot& plot);

}  // namespace tumble::render::detail
