#include "app/frame/overlay_fit.hpp"

#include <algorithm>
#include <cmath>

#include "render/overlay_layout.hpp"

namespace tumble::app {

// ImGui's layout with the style scaled by font_px / 13: window padding 8, item spacing 4,
// frame padding 4 x 3 at 13 px.
// A compact panel: its lines alone, with the tight padding and spacing the renderer gives it.
OverlayPanelSize compact_panel_size(const render::OverlayPanel& panel) {
  const float f = std::round(std::clamp(panel.font_px, render::kMinFontPx, render::kMaxFontPx));
  const float padding = render::compact_panel_padding(f);
  std::size_t chars = 0;
  for (const std::string& line : panel.lines) chars = std::max(chars, line.size());
  const auto lines = static_cast<float>(panel.lines.size());
  OverlayPanelSize size;
  size.width = render::overlay_text_width(chars, f) + 2.0f * padding;
  size.height =
      2.0f * padding + lines * f + std::max(0.0f, lines - 1.0f) * render::compact_panel_spacing(f);
  return size;
}

OverlayPanelSize overlay_panel_size(const render::OverlayPanel& panel) {
  if (panel.compact) return compact_panel_size(panel);
  const float f = panel.font_px;
  const float u = f / render::kDefaultFontPx;
  std::size_t chars = panel.title.size() + 1;
  for (const std::string& line : panel.lines) chars = std::max(chars, line.size());
  for (const render::Plot& plot : panel.plots) chars = std::max(chars, plot.name.size() + 12);
  OverlayPanelSize size;
  size.width = render::overlay_text_width(chars, f) + 16.0f * u;
  const float line = f + 4.0f * u;
  size.height = (f + 6.0f * u) + 16.0f * u + static_cast<float>(panel.lines.size()) * line;
  for (const render::Plot& plot : panel.plots) size.height += line + plot.height_px + 4.0f * u;
  return size;
}

void fit_overlay_panel(render::OverlayPanel& panel, std::size_t first_droppable, int width,
                       int height, double coverage) {
  const double budget = coverage * static_cast<double>(width) * height;
  const auto area = [&] {
    const OverlayPanelSize size = overlay_panel_size(panel);
    return static_cast<double>(std::min(size.width, static_cast<float>(width))) * size.height;
  };
  std::size_t legend = panel.lines.size() - std::min(first_droppable, panel.lines.size());
  while (legend > 0 && area() > budget) {
    --legend;
    panel.lines.erase(panel.lines.begin() + static_cast<long>(panel.lines.size() - 1));
  }
  for (render::Plot& plot : panel.plots) {
    if (area() > budget) plot.height_px = std::min(plot.height_px, 2.0f * panel.font_px);
  }
  while (!panel.plots.empty() && area() > budget) panel.plots.pop_back();
  const float margin = panel.position_px.x();
  panel.width_px =
      std::min(overlay_panel_size(panel).width, static_cast<float>(width) - 2.0f * margin);
}

}  // namespace tumble::app
