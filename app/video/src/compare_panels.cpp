#include "app/video/compare_panels.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "app/frame/overlay_fit.hpp"
#include "render/overlay_layout.hpp"

namespace tumble::app {

namespace {

/// The gap between a panel and the tile's corner: proportional to the text, the padding of a
/// compact panel.
float panel_margin(const render::OverlayPanel& panel) {
  return panel.compact ? render::compact_panel_padding(panel.font_px)
                       : 10.0f * panel.font_px / render::kDefaultFontPx;
}

/// The largest text height (down to the minimum) at which `panel` is at most `width` wide
/// with its margins; keeps the margin proportional to the text.
void shrink_to_width(render::OverlayPanel& panel, int width) {
  for (;;) {
    const float margin = panel_margin(panel);
    panel.position_px = {margin, margin};
    const float room = static_cast<float>(width) - 2.0f * margin;
    if (overlay_panel_size(panel).width <= room || panel.font_px <= render::kMinFontPx) return;
    panel.font_px = std::max(render::kMinFontPx, panel.font_px - 1.0f);
  }
}

/// True when `panel` lies inside the tile and covers at most kTileCoverageBudget of it.
bool fits_tile(const render::OverlayPanel& panel, int width, int height) {
  const OverlayPanelSize size = overlay_panel_size(panel);
  const float margin = panel_margin(panel);
  return size.width + 2.0f * margin <= static_cast<float>(width) &&
         size.height + 2.0f * margin <= static_cast<float>(height) &&
         static_cast<double>(size.width) * size.height <=
             kTileCoverageBudget * static_cast<double>(width) * height;
}

/// The compact corner label: the integrator on a line of its own, the step and the time on
/// the next (on two when they do not fit side by side), then the blow-up; no plots.
void fit_compact(render::OverlayPanel& panel, const TileText& text, std::string blow_up, int width,
                 int height) {
  panel.compact = true;
  panel.plots.clear();
  const std::string step = "dt " + text.dt + " s";
  const std::string time = "t = " + text.time + " s";
  panel.lines = {text.integrator, step + ", " + time};
  if (!blow_up.empty()) panel.lines.push_back(blow_up);
  shrink_to_width(panel, width);
  const float margin = panel_margin(panel);
  if (overlay_panel_size(panel).width + 2.0f * margin > static_cast<float>(width)) {
    panel.lines[1] = step;
    panel.lines.insert(panel.lines.begin() + 2, time);
  }
  // Smaller text, down to the minimum, while it covers too much.
  while (!fits_tile(panel, width, height) && panel.font_px > render::kMinFontPx) {
    panel.font_px = std::max(render::kMinFontPx, panel.font_px - 1.0f);
    shrink_to_width(panel, width);
  }
}

}  // namespace

void fit_tile_panel(render::OverlayPanel& panel, const TileText& text, int tile_width,
                    int tile_height, bool compact) {
  const float font_px = panel.font_px;
  std::string blow_up = text.blow_up.empty() ? "" : "blew up at t = " + text.blow_up + " s";
  // The full panel: integrator and step as its title, the time (and blow-up) as its lines.
  panel.compact = false;
  panel.title = text.integrator + ", dt = " + text.dt + " s";
  panel.lines = {"t = " + text.time + " s"};
  if (!blow_up.empty()) panel.lines.push_back(blow_up);
  shrink_to_width(panel, tile_width);
  const float plot_height = std::clamp(0.1f * static_cast<float>(tile_height), 2.0f * panel.font_px,
                                       4.0f * panel.font_px);
  for (render::Plot& plot : panel.plots) plot.height_px = plot_height;
  fit_overlay_panel(panel, panel.lines.size(), tile_width, tile_height, kTileCoverageBudget);
  if (compact || !fits_tile(panel, tile_width, tile_height)) {
    panel.font_px = font_px;
    fit_compact(panel, text, std::move(blow_up), tile_width, tile_height);
  }
  const float margin = panel_margin(panel);
  panel.width_px =
      std::min(overlay_panel_size(panel).width, static_cast<float>(tile_width) - 2.0f * margin);
}

void fit_tile_panels(std::vector<render::DrawList>& lists, const std::vector<TileText>& texts,
                     int tile_width, int tile_height) {
  bool compact = false;
  for (std::size_t i = 0; i < lists.size(); ++i) {
    if (lists[i].panels.empty()) continue;
    render::OverlayPanel trial = lists[i].panels.front();
    fit_tile_panel(trial, texts.at(i), tile_width, tile_height);
    compact = compact || trial.compact;
  }
  std::size_t plots = std::numeric_limits<std::size_t>::max();
  for (std::size_t i = 0; i < lists.size(); ++i) {
    if (lists[i].panels.empty()) continue;
    render::OverlayPanel& panel = lists[i].panels.front();
    fit_tile_panel(panel, texts[i], tile_width, tile_height, compact);
    plots = std::min(plots, panel.plots.size());
  }
  for (render::DrawList& list : lists) {
    if (list.panels.empty() || list.panels.front().plots.size() <= plots) continue;
    render::OverlayPanel& panel = list.panels.front();
    panel.plots.resize(plots);
    panel.width_px = std::min(overlay_panel_size(panel).width,
                              static_cast<float>(tile_width) - 2.0f * panel.position_px.x());
  }
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
