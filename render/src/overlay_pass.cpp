#include "overlay_pass.hpp"

#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "backends/imgui_impl_opengl3.h"
#include "overlay_plot.hpp"
#include "render/camera_math.hpp"
#include "render/overlay_layout.hpp"

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

int font_key(float font_px) {
  return static_cast<int>(std::lround(std::clamp(font_px, kMinFontPx, kMaxFontPx)));
}

/// A label's text height: its own, or (0) the frame's default.
float label_font_px(const Label& label, int width, int height) {
  return label.font_px > 0.0f ? label.font_px : overlay_font_px(width, height);
}

}  // namespace

std::string OverlayPass::panel_id(const OverlayPanel& panel, int index) {
  // The size and form are part of the id: a panel drawn at a new size is laid out afresh.
  return panel.title + "##panel" + std::to_string(index) + "@" +
         std::to_string(font_key(panel.font_px)) + (panel.compact ? "c" : "");
}

ImFont* OverlayPass::font(float font_px) const {
  return fonts_.at(font_key(font_px));
}

void OverlayPass::ensure_fonts(const DrawList& frame, int width, int height) {
  std::vector<int> sizes;
  for (const OverlayPanel& panel : frame.panels) sizes.push_back(font_key(panel.font_px));
  for (const Label& label : frame.labels) {
    sizes.push_back(font_key(label_font_px(label, width, height)));
  }
  bool added = false;
  ImGuiIO& io = ImGui::GetIO();
  for (int px : sizes) {
    if (fonts_.count(px) != 0) continue;
    // The default font rasterised at the size itself: scaling a 13 px bitmap would blur it.
    ImFontConfig config;
    config.SizePixels = static_cast<float>(px);
    fonts_[px] = io.Fonts->AddFontDefault(&config);
    added = true;
  }
  if (!added) return;
  ImGui_ImplOpenGL3_DestroyFontsTexture();
  ImGui_ImplOpenGL3_CreateFontsTexture();
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
  base_style_ = std::make_unique<ImGuiStyle>(style);
  if (!ImGui_ImplOpenGL3_Init("#version 330 core")) {
    ImGui::DestroyContext(context_);
    throw std::runtime_error("renderer: ImGui OpenGL3 backend failed to initialise");
  }
  // The default size first, then the GL objects with its atlas.
  ImFontConfig config;
  config.SizePixels = kDefaultFontPx;
  fonts_[font_key(kDefaultFontPx)] = io.Fonts->AddFontDefault(&config);
  ImGui_ImplOpenGL3_CreateDeviceObjects();
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
    // Paddings, spacings and rounding follow the text size; a compact panel packs its lines.
    const auto px = static_cast<float>(font_key(panel.font_px));
    ImGuiStyle& style = ImGui::GetStyle();
    style = *base_style_;
    style.ScaleAllSizes(px / kDefaultFontPx);
    if (panel.compact) {
      const float padding = compact_panel_padding(px);
      style.WindowPadding = ImVec2(padding, padding);
      style.ItemSpacing.y = compact_panel_spacing(px);
      style.WindowMinSize = ImVec2(1.0f, 1.0f);
      style.WindowRounding = std::min(style.WindowRounding, padding);
    }
    ImGui::PushFont(font(panel.font_px));
    ImGui::SetNextWindowPos(ImVec2(panel.position_px.x(), panel.position_px.y()));
    ImGui::SetNextWindowSizeConstraints(ImVec2(panel.width_px, 0.0f),
                                        ImVec2(panel.width_px, FLT_MAX));
    const bool title_bar = !panel.title.empty() && !panel.compact;
    ImGui::Begin(id.c_str(), nullptr, title_bar ? flags : flags | ImGuiWindowFlags_NoTitleBar);
    for (const std::string& line : panel.lines) ImGui::TextUnformatted(line.c_str());
    for (const Plot& plot : panel.plots) draw_plot(plot);
    ImGui::End();
    ImGui::PopFont();
  }
  ImGui::GetStyle() = *base_style_;
  draw_labels(frame, width, height);
  ImGui::Render();
}

/// Labels: text with a one-pixel dark shadow, anchored in 3D or placed on screen.
void OverlayPass::draw_labels(const DrawList& frame, int width, int height) {
  ImDrawList* draw_list = ImGui::GetForegroundDrawList();
  for (const Label& label : frame.labels) {
    const float px = static_cast<float>(font_key(label_font_px(label, width, height)));
    ImVec2 position(label.screen_px.x(), label.screen_px.y());
    if (label.anchor) {
      const Eigen::Vector3f pixel = project_to_pixels(frame.camera, width, height, *label.anchor);
      if (!(pixel.z() > 0.0f)) continue;  // behind the camera
      position = ImVec2(pixel.x() + 0.3f * px, pixel.y() - px - 0.15f * px);
    }
    const float offset = std::max(1.0f, std::round(px / kDefaultFontPx));
    const ImVec2 shadow(position.x + offset, position.y + offset);
    draw_list->AddText(font(px), px, shadow,
                       IM_COL32(0, 0, 0, static_cast<int>(180 * label.colour.a)),
                       label.text.c_str());
    draw_list->AddText(font(px), px, position, to_imgui(label.colour), label.text.c_str());
  }
}

void OverlayPass::draw(const DrawList& frame, int width, int height) {
  ContextGuard guard(context_);
  ensure_fonts(frame, width, height);
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
