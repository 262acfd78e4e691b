#include "app/commands/compare_panels.hpp"

#include <algorithm>
#include <cmath>

#include "app/frame/overlay_fit.hpp"
#include "render/overlay_layout.hpp"

namespace tumble::app {

namespace {

/// The largest text height (down to the minimum) at which `panel` is at most `width` wide
/// with its margins; keeps the margin proportional to the text.
void shrink_to_width(render::OverlayPanel& panel, int width) {
  for (;;) {
    const float margin = 10.0f * panel.font_px / render::kDefaultFontPx;
    panel.position_px = {margin, margin};
    const float room = static_cast<float>(width) - 2.0f * margin;
    if (overlay_panel_size(panel).width <= room || panel.font_px <= render::kMinFontPx) return;
    panel.font_px = std::max(render::kMinFontPx, panel.font_px - 1.0f);
  }
}

}  // namespace

void fit_tile_panel(render::OverlayPanel& panel, std::string title, std::vector<std::string> lines,
                    int tile_width, int tile_height) {
  panel.title = std::move(title);
  panel.lines = std::move(lines);
  shrink_to_width(panel, tile_width);
  const float plot_height = std::clamp(0.1f * static_cast<float>(tile_height), 2.0f * panel.font_px,
                                       4.0f * panel.font_px);
  for (render::Plot& plot : panel.plots) plot.height_px = plot_height;
  fit_overlay_panel(panel, panel.lines.size(), tile_width, tile_height);
}

void share_plot_scales(std::vector<render::DrawList>& lists) {
  for (std::size_t k = 0;; ++k) {
    // The common range of plot k over every tile that has it.
    float low = HUGE_VALF;
    float high = -HUGE_VALF;
    bool any = false;
    for (const render::DrawList& list : lists) {
      if (list.panels.empty() || list.panels.front().plots.size() <= k) continue;
      const render::Plot& plot = list.panels.front().plots[k];
      any = true;
      for (float v : plot.values) {
        if (!std::isfinite(v)) continue;
        const float a =
            plot.axis == render::PlotAxis::kLog ? std::max(std::abs(v), plot.log_floor) : v;
        low = std::min(low, a);
        high = std::max(high, a);
      }
    }
    if (!any) return;
    if (!(low <= high)) continue;
    for (render::DrawList& list : lists) {
      if (list.panels.empty() || list.panels.front().plots.size() <= k) continue;
      render::Plot& plot = list.panels.front().plots[k];
      plot.min = low;
      plot.max = high;
    }
  }
}

void fit_legend_panel(render::OverlayPanel& legend, int width, int height, double font_scale) {
  legend.font_px = render::overlay_font_px(width, height, font_scale);
  shrink_to_width(legend, width);
  legend.width_px = std::min(overlay_panel_size(legend).width,
                             static_cast<float>(width) - 2.0f * legend.position_px.x());
}

}  // namespace tumble::app
