#include "overlay_pass.hpp"

#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "backends/imgui_impl_opengl3.h"
#include "render/camera_math.hpp"

namespace tumble::render::detail {

namespace {

ImU32 to_imgui(const Rgba& c) {
  return ImGui::ColorConvertFloat4ToU32(ImVec4(c.r, c.g, c.b, c.a));
}

/// Makes an ImGui context current for the lifetime of the guard, restoring the previous one.
class ContextGuard {
 public:
  explicit ContextGuard(ImGuiContext* context) : previous_(ImGui::GetCurrentContext()) {
    ImGui::SetCurrentContext(context);
  }
  ~ContextGuard() { ImGui::SetCurrentContext(previous_); }
  ContextGuard(const ContextGuard&) = delete;
  ContextGuard& operator=(const ContextGuard&) = delete;

 private:
  ImGuiContext* previous_;
};

}  // namespace

std::string OverlayPass::panel_id(const OverlayPanel& panel, int index) {
  return panel.title + "##panel" + std::to_string(index);
}

OverlayPass::OverlayPass() {
  ImGuiContext* previous = ImGui::GetCurrentContext();
  context_ = ImGui::CreateContext();  // also makes it current
  ImGui::SetCurrentContext(previous);
  ContextGuard guard(context_);
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // nothing on disk
  io.LogFilename = nullptr;
  ImGui::StyleColorsDark();
  ImGuiStyle& style = ImGui::GetStyle();
  style.WindowRounding = 4.0f;
  style.Colors[ImGuiCol_WindowBg].w = 0.72f;
  style.Colors[ImGuiCol_FrameBg] = ImVec4(0.10f, 0.10f, 0.12f, 0.60f);
  if (!ImGui_ImplOpenGL3_Init("#version 330 core")) {
    ImGui::DestroyContext(context_);
    throw std::runtime_error("renderer: ImGui OpenGL3 backend failed to initialise");
  }
}

OverlayPass::~OverlayPass() {
  ContextGuard guard(context_);
  ImGui_ImplOpenGL3_Shutdown();
  ImGui::DestroyContext(context_);
}

void OverlayPass::build(const DrawList& frame, int width, int height) {
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = ImVec2(static_cast<float>(width), static_cast<float>(height));
  io.DeltaTime = 1.0f / 60.0f;
  ImGui_ImplOpenGL3_NewFrame();
  ImGui::NewFrame();

  // Panels: fixed width, height fitted to their content.
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize |
                                 ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoSavedSettings |
                                 ImGuiWindowFlags_AlwaysAutoResize |
                                 ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav;
  int index = 0;
  for (const OverlayPanel& panel : frame.panels) {
    const std::string id = panel_id(panel, index++);
    ImGui::SetNextWindowPos(ImVec2(panel.position_px.x(), panel.position_px.y()));
    ImGui::SetNextWindowSizeConstraints(ImVec2(panel.width_px, 0.0f),
                                        ImVec2(panel.width_px, FLT_MAX));
    ImGui::Begin(id.c_str(), nullptr,
                 panel.title.empty() ? flags | ImGuiWindowFlags_NoTitleBar : flags);
    for (const std::string& line : panel.lines) ImGui::TextUnformatted(line.c_str());
    for (const Plot& plot : panel.plots) {
      if (plot.values.empty()) continue;
      const auto [low, high] = std::minmax_element(plot.values.begin(), plot.values.end());
      char caption[160];
      std::snprintf(caption, sizeof caption, "%s  %.4g", plot.name.c_str(),
                    static_cast<double>(plot.values.back()));
      const std::string plot_id = "##plot" + plot.name;
      ImGui::PlotLines(plot_id.c_str(), plot.values.data(), static_cast<int>(plot.values.size()), 0,
                       caption, plot.min.value_or(*low), plot.max.value_or(*high),
                       ImVec2(ImGui::GetContentRegionAvail().x, plot.height_px));
    }
    ImGui::End();
  }

  // Labels: text with a one-pixel dark shadow, anchored in 3D or placed on screen.
  ImDrawList* draw_list = ImGui::GetForegroundDrawList();
  for (const Label& label : frame.labels) {
    ImVec2 position(label.screen_px.x(), label.screen_px.y());
    if (label.anchor) {
      const Eigen::Vector3f pixel = project_to_pixels(frame.camera, width, height, *label.anchor);
      if (!(pixel.z() > 0.0f)) continue;  // behind the camera
      position = ImVec2(pixel.x() + 4.0f, pixel.y() - ImGui::GetFontSize() - 2.0f);
    }
    const ImVec2 shadow(position.x + 1.0f, position.y + 1.0f);
    draw_list->AddText(shadow, IM_COL32(0, 0, 0, static_cast<int>(180 * label.colour.a)),
                       label.text.c_str());
    draw_list->AddText(position, to_imgui(label.colour), label.text.c_str());
  }
  ImGui::Render();
}

void OverlayPass::draw(const DrawList& frame, int width, int height) {
  ContextGuard guard(context_);
  // ImGui sizes an auto-fitting window one frame after it first appears: lay out a hidden
  // frame first whenever a panel is new, so that its first image already shows it.
  bool new_panel = false;
  for (int i = 0; i < static_cast<int>(frame.panels.size()); ++i) {
    new_panel |= known_panels_.insert(panel_id(frame.panels[i], i)).second;
  }
  if (new_panel) build(frame, width, height);
  build(frame, width, height);
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

}  // namespace tumble::render::detail
