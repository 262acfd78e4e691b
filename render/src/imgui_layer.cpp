#include "render/imgui_layer.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "backends/imgui_impl_opengl3.h"
#include "render/overlay_layout.hpp"

namespace tumble::render {

ImGuiLayer::ImGuiLayer(Renderer& renderer) : renderer_(renderer) {
  context_ = ImGui::CreateContext();  // also makes it current
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // nothing on disk
  io.LogFilename = nullptr;
  ImGui::StyleColorsDark();
  ImGui::GetStyle().WindowRounding = 4.0f;
  base_style_ = std::make_unique<ImGuiStyle>(ImGui::GetStyle());
  ImFontConfig config;
  config.SizePixels = font_px_;
  io.FontDefault = io.Fonts->AddFontDefault(&config);
  bool started = false;
  renderer_.with_context([&] {
    // The device objects (and the font texture) now, so that a new font size only replaces
    // the texture.
    started =
        ImGui_ImplOpenGL3_Init("#version 330 core") && ImGui_ImplOpenGL3_CreateDeviceObjects();
  });
  if (!started) {
    ImGui::DestroyContext(context_);
    throw std::runtime_error("ImGui layer: the OpenGL3 backend failed to initialise");
  }
}

ImGuiLayer::~ImGuiLayer() {
  ImGuiContext* previous = ImGui::GetCurrentContext();
  ImGui::SetCurrentContext(context_);
  renderer_.with_context([] { ImGui_ImplOpenGL3_Shutdown(); });
  ImGui::DestroyContext(context_);
  if (previous != context_) ImGui::SetCurrentContext(previous);
}

void ImGuiLayer::set_font_px(float px) {
  wanted_px_ = std::round(std::clamp(px, kMinFontPx, kMaxFontPx));
}

void ImGuiLayer::apply_font_size() {
  if (wanted_px_ == font_px_) return;
  font_px_ = wanted_px_;
  ImGuiIO& io = ImGui::GetIO();
  io.Fonts->Clear();
  ImFontConfig config;
  config.SizePixels = font_px_;
  io.FontDefault = io.Fonts->AddFontDefault(&config);
  ImGui_ImplOpenGL3_DestroyFontsTexture();
  ImGui_ImplOpenGL3_CreateFontsTexture();
  ImGuiStyle& style = ImGui::GetStyle();
  style = *base_style_;
  style.ScaleAllSizes(font_px_ / kDefaultFontPx);
}

ExtraPass ImGuiLayer::pass(float delta_seconds, std::function<void()> build,
                           std::function<void()> after_new_frame, Image* before) {
  ExtraPass extra;
  extra.before = before;
  extra.draw = [this, delta_seconds, build = std::move(build),
                after_new_frame = std::move(after_new_frame)](int width, int height) {
    ImGuiContext* previous = ImGui::GetCurrentContext();
    ImGui::SetCurrentContext(context_);
    apply_font_size();
    ImGuiIO& io = ImGui::GetIO();
    io.DisplaySize = ImVec2(static_cast<float>(width), static_cast<float>(height));
    io.DeltaTime = delta_seconds > 0.0f ? delta_seconds : 1.0f / 60.0f;
    ImGui_ImplOpenGL3_NewFrame();
    ImGui::NewFrame();
    if (after_new_frame) after_new_frame();
    if (build) build();
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    ImGui::SetCurrentContext(previous);
  };
  return extra;
}

}  // namespace tumble::render
