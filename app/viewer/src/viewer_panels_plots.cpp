// The viewer's "Inspector" and "Plots" panel sections, and the plot they draw.
#include "app/viewer/viewer_panels.hpp"

#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <string>
#include <vector>

#include "render/overlay_layout.hpp"
#include "viewer_panels_common.hpp"

namespace tumble::app::viewer {
namespace {

/// One line of a plot.
struct Series {
  const char* name;
  const std::vector<float>* values;
  ImU32 colour;
};

/// Several series in one frame filling the panel's width, each decimated to a min/max pair per
/// two pixels (so a long history costs the same as a short one: llvmpipe pays per triangle),
/// with the latest values as a legend above it.
void plot(const std::vector<Series>& series, float height) {
  // Legend: the latest value of each series in its colour.
  for (std::size_t k = 0; k < series.size(); ++k) {
    if (k > 0) ImGui::SameLine();
    const std::vector<float>& values = *series[k].values;
    ImGui::PushStyleColor(ImGuiCol_Text, series[k].colour);
    ImGui::Text("%s %.3g", series[k].name, values.empty() ? 0.0 : double{values.back()});
    ImGui::PopStyleColor();
  }
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const float width = ImGui::GetContentRegionAvail().x;
  ImGui::Dummy(ImVec2(width, height));
  ImDrawList* draw = ImGui::GetWindowDrawList();
  draw->AddRectFilled(origin, ImVec2(origin.x + width, origin.y + height),
                      ImGui::GetColorU32(ImGuiCol_FrameBg));

  // A common vertical range; a flat one is widened so a constant draws mid-height.
  float low = FLT_MAX;
  float high = -FLT_MAX;
  for (const Series& line : series) {
    for (float v : *line.values) {
      if (std::isfinite(v)) {
        low = std::min(low, v);
        high = std::max(high, v);
      }
    }
  }
  if (low > high) return;
  if (high - low < 1e-30f) {
    low -= 1.0f;
    high += 1.0f;
  }
  const int buckets = std::max(1, static_cast<int>(width / 2.0f));
  std::vector<ImVec2> points;
  for (const Series& line : series) {
    const std::vector<float>& values = *line.values;
    if (values.size() < 2) continue;
    points.clear();
    const auto to_screen = [&](double fraction, float v) {
      return ImVec2(origin.x + static_cast<float>(fraction) * width,
                    origin.y + height - 2.0f - (v - low) / (high - low) * (height - 4.0f));
    };
    const std::size_t n = values.size();
    for (std::size_t i : render::min_max_decimation(values, buckets)) {
      points.push_back(to_screen(static_cast<double>(i) / static_cast<double>(n - 1), values[i]));
    }
    draw->AddPolyline(points.data(), static_cast<int>(points.size()), line.colour, ImDrawFlags_None,
                      1.0f);
  }
}

}  // namespace

void Panels::inspector_section(Viewer& viewer) {
  const Session& session = viewer.session();
  if (!ImGui::CollapsingHeader("Inspector")) return;
  const auto& bodies = session.compiled().bodies;
  const std::size_t body = std::min(viewer.selected_body, bodies.size() - 1);
  ImGui::TextColored(kDimColour, "body: %s (choose it under Initial state)",
                     bodies[body].name.c_str());
  for (const std::string& warning : session.inspector_warnings(body)) {
    ImGui::TextColored(kErrorColour, "warning: %s", warning.c_str());
  }
  if (report_generation_ != session.generation() || report_body_ != body) {
    report_ = session.inspector_text(body);
    report_generation_ = session.generation();
    report_body_ = body;
  }
  const std::string& report = report_;
  ImGui::BeginChild("report", ImVec2(0.0f, scaled(220.0f)), true,
                    ImGuiWindowFlags_HorizontalScrollbar);
  ImGui::TextUnformatted(report.c_str());
  ImGui::EndChild();
}

void Panels::plots_section(Viewer& viewer) {
  Session& session = viewer.session();
  if (!ImGui::CollapsingHeader("Plots", ImGuiTreeNodeFlags_DefaultOpen)) return;
  const History& history = session.history();
  ImGui::TextColored(kDimColour, "relative drift of the invariants");
  plot({{"energy", &history.energy_drift, IM_COL32(250, 200, 60, 255)},
        {"|L|", &history.momentum_drift, IM_COL32(200, 140, 255, 255)}},
       scaled(60.0f));
  const auto& bodies = session.compiled().bodies;
  ImGui::TextColored(kDimColour, "w of %s in its body frame (rad/s)",
                     bodies[std::min(session.plotted_body(), bodies.size() - 1)].name.c_str());
  plot({{"x", &history.omega[0], IM_COL32(240, 90, 80, 255)},
        {"y", &history.omega[1], IM_COL32(100, 220, 100, 255)},
        {"z", &history.omega[2], IM_COL32(100, 150, 255, 255)}},
       scaled(80.0f));
  if (viewer.selected_body != session.plotted_body())
    session.set_plotted_body(viewer.selected_body);
}

}  // namespace tumble::app::viewer
