#include "overlay_plot.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "render/overlay_layout.hpp"

namespace tumble::render::detail {

namespace {

/// The vertical axis: values are mapped through `to_axis` (identity or log10|v|) onto
/// [low, high] and labelled at `ticks` (axis coordinates).
struct Axis {
  bool log = false;
  float floor = 1e-16f;
  double low = 0.0;
  double high = 1.0;
  std::vector<double> ticks;

  double to_axis(float v) const {
    if (!log) return static_cast<double>(v);
    return std::log10(std::max(static_cast<double>(std::abs(v)), static_cast<double>(floor)));
  }
};

std::string tick_text(const Axis& axis, double tick) {
  char text[32];
  if (axis.log) {
    std::snprintf(text, sizeof text, "1e%d", static_cast<int>(std::lround(tick)));
  } else {
    std::snprintf(text, sizeof text, "%.2g", tick);
  }
  return text;
}

/// The axis of `plot`: its fixed bounds or the data's finite range; a log axis is widened to
/// whole decades, a flat linear one by one unit either side; at most `max_ticks` ticks.
Axis make_axis(const Plot& plot, int max_ticks) {
  Axis axis;
  axis.log = plot.axis == PlotAxis::kLog;
  axis.floor = plot.log_floor > 0.0f ? plot.log_floor : 1e-16f;
  double low = HUGE_VAL;
  double high = -HUGE_VAL;
  for (float v : plot.values) {
    if (!std::isfinite(v)) continue;
    low = std::min(low, axis.to_axis(v));
    high = std::max(high, axis.to_axis(v));
  }
  if (plot.min) low = axis.to_axis(*plot.min);
  if (plot.max) high = axis.to_axis(*plot.max);
  if (!(low <= high)) low = high = 0.0;
  max_ticks = std::max(2, max_ticks);
  if (axis.log) {
    low = std::floor(low);
    high = std::max(std::ceil(high), low + 1.0);
    const double step = std::ceil((high - low) / (max_ticks - 1));
    high = low + step * std::ceil((high - low) / step);
    for (double t = low; t <= high + 0.5; t += step) axis.ticks.push_back(t);
  } else {
    if (high - low < 1e-30) {
      low -= 1.0;
      high += 1.0;
    }
    axis.ticks = {low, high};
    if (max_ticks >= 3) axis.ticks.insert(axis.ticks.begin() + 1, 0.5 * (low + high));
  }
  axis.low = low;
  axis.high = high;
  return axis;
}

}  // namespace

void draw_plot(const Plot& plot) {
  // Caption: the name and the current value, above the curve.
  const float font_px = ImGui::GetFontSize();
  if (plot.values.empty()) {
    ImGui::Text("%s  -", plot.name.c_str());
  } else {
    ImGui::Text("%s  %.3g", plot.name.c_str(), static_cast<double>(plot.values.back()));
  }
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const float width = ImGui::GetContentRegionAvail().x;
  const float height = std::max(plot.height_px, font_px);
  ImGui::Dummy(ImVec2(width, height));

  // Gutter for the tick labels, then the curve's frame.
  const int max_ticks = std::clamp(static_cast<int>(height / (1.1f * font_px)), 2, 5);
  const Axis axis = make_axis(plot, max_ticks);
  float gutter = 0.0f;
  for (double tick : axis.ticks) {
    gutter = std::max(gutter, ImGui::CalcTextSize(tick_text(axis, tick).c_str()).x);
  }
  gutter += 0.4f * font_px;
  const ImVec2 top_left(origin.x + gutter, origin.y);
  const ImVec2 bottom_right(origin.x + width, origin.y + height);
  ImDrawList* draw = ImGui::GetWindowDrawList();
  draw->AddRectFilled(top_left, bottom_right, ImGui::GetColorU32(ImGuiCol_FrameBg));
  const float inset = 0.15f * font_px;
  const auto to_y = [&](double a) {
    const double f = (a - axis.low) / (axis.high - axis.low);
    return static_cast<float>(bottom_right.y - inset - f * (height - 2.0f * inset));
  };

  // Ticks: a faint grid line and a right-aligned label, kept inside the plot's height.
  const ImU32 grid = IM_COL32(255, 255, 255, 40);
  const ImU32 label = ImGui::GetColorU32(ImGuiCol_TextDisabled);
  for (double tick : axis.ticks) {
    const float y = to_y(tick);
    draw->AddLine(ImVec2(top_left.x, y), ImVec2(bottom_right.x, y), grid);
    const std::string text = tick_text(axis, tick);
    const ImVec2 size = ImGui::CalcTextSize(text.c_str());
    const float text_y = std::clamp(y - 0.5f * size.y, origin.y, bottom_right.y - size.y);
    draw->AddText(ImVec2(top_left.x - 0.2f * font_px - size.x, text_y), label, text.c_str());
  }

  // The curve, decimated to the pixel columns.
  const std::size_t n = plot.values.size();
  if (n < 2) return;
  const float curve_width = bottom_right.x - top_left.x;
  std::vector<float> mapped(n);
  for (std::size_t i = 0; i < n; ++i) {
    const float v = plot.values[i];
    mapped[i] =
        std::isfinite(v) ? static_cast<float>(std::clamp(axis.to_axis(v), axis.low, axis.high)) : v;
  }
  std::vector<ImVec2> points;
  for (std::size_t i : min_max_decimation(mapped, static_cast<int>(curve_width / 2.0f))) {
    if (!std::isfinite(mapped[i])) continue;
    points.emplace_back(
        top_left.x + curve_width * static_cast<float>(i) / static_cast<float>(n - 1),
        to_y(static_cast<double>(mapped[i])));
  }
  draw->AddPolyline(points.data(), static_cast<int>(points.size()),
                    ImGui::GetColorU32(ImGuiCol_PlotLines), ImDrawFlags_None,
                    std::max(1.0f, font_px / kDefaultFontPx));
}

}  // namespace tumble::render::detail
