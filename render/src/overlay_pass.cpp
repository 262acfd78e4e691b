#include "overlay_pass.hpp"

#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "backends/imgui_impl_opengl3.h"
#include "overlay_plot.hpp"
#include "render/camera_math.hpp"
#include "render/offscreen_context.hpp"
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

/// Appends the bytes of `count` objects at `data` to `key`.
template <typename T>
void append_bytes(std::vector<unsigned char>& key, const T* data, std::size_t count) {
  const auto* bytes = reinterpret_cast<const unsigned char*>(data);
  key.insert(key.end(), bytes, bytes + count * sizeof(T));
}

/// A window's decorations are its list's first command, drawn before its content (a list of
/// one command has none).
bool has_decorations(const ImDrawList& list) {
  return list.CmdBuffer.Size >= 2 && list.CmdBuffer[0].UserCallback == nullptr;
}

bool overlap(const PixelBox& a, const PixelBox& b) {
  return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
}

/// Renders `data` with only the commands `keep(list, command)` accepts: the others' element
/// counts are 0 for the call.
template <typename Keep>
void render_commands(ImDrawData& data, Keep keep) {
  std::vector<unsigned int> counts;
  for (int l = 0; l < data.CmdListsCount; ++l) {
    for (int c = 0; c < data.CmdLists[l]->CmdBuffer.Size; ++c) {
      ImDrawCmd& command = data.CmdLists[l]->CmdBuffer[c];
      counts.push_back(command.ElemCount);
      if (!keep(l, c)) command.ElemCount = 0;
    }
  }
  ImGui_ImplOpenGL3_RenderDrawData(&data);
  std::size_t i = 0;
  for (int l = 0; l < data.CmdListsCount; ++l) {
    for (ImDrawCmd& command : data.CmdLists[l]->CmdBuffer) command.ElemCount = counts[i++];
  }
}

/// The box (GL's pixel coordinates, one pixel of margin) holding vertices `first`..`last` of
/// `list`, in a `width` x `height` frame.
PixelBox vertex_box(const ImDrawList& list, int first, int last, int width, int height) {
  float x0 = FLT_MAX, y0 = FLT_MAX, x1 = -FLT_MAX, y1 = -FLT_MAX;
  for (int v = first; v < last; ++v) {
    const ImVec2& p = list.VtxBuffer[v].pos;
    x0 = std::min(x0, p.x);
    x1 = std::max(x1, p.x);
    y0 = std::min(y0, p.y);
    y1 = std::max(y1, p.y);
  }
  if (!(x0 <= x1 && y0 <= y1)) return PixelBox{};
  const auto clamp = [](float v, int limit) {
    return static_cast<int>(std::clamp(v, 0.0f, static_cast<float>(limit)));
  };
  return {clamp(std::floor(x0) - 1.0f, width),
          clamp(static_cast<float>(height) - std::ceil(y1) - 1.0f, height),
          clamp(std::ceil(x1) + 1.0f, width),
          clamp(static_cast<float>(height) - std::floor(y0) + 1.0f, height)};
}

/// Each draw list's box (of its vertices), the empty ones left out.
std::vector<PixelBox> draw_data_boxes(const ImDrawData& data, int width, int height) {
  std::vector<PixelBox> boxes;
  for (int l = 0; l < data.CmdListsCount; ++l) {
    const ImDrawList& list = *data.CmdLists[l];
    const PixelBox box = vertex_box(list, 0, list.VtxBuffer.Size, width, height);
    if (box.x0 < box.x1 && box.y0 < box.y1) boxes.push_back(box);
  }
  return boxes;
}

}  // namespace

std::optional<std::vector<OverlayPass::Decorations>> OverlayPass::decorations(
    const ImDrawData& data, int width, int height, const OverlayUnder& under) {
  if (under.layers == 0 || !under.drawn || data.DisplayPos.x != 0.0f || data.DisplayPos.y != 0.0f) {
    return std::nullopt;
  }
  std::vector<Decorations> found;
  std::vector<PixelBox> lists;  // every list's box so far
  for (int l = 0; l < data.CmdListsCount; ++l) {
    const ImDrawList& list = *data.CmdLists[l];
    const PixelBox whole = vertex_box(list, 0, list.VtxBuffer.Size, width, height);
    if (has_decorations(list)) {
      // Drawn before the earlier lists' rest: it must not overlap them.
      for (const PixelBox& earlier : lists) {
        if (overlap(whole, earlier)) return std::nullopt;
      }
      const ImDrawCmd& first = list.CmdBuffer[0];
      const ImDrawIdx* indices = list.IdxBuffer.Data + first.IdxOffset;
      const ImDrawIdx* end = indices + first.ElemCount;
      const int last =
          static_cast<int>(first.VtxOffset) +
          (first.ElemCount > 0 ? static_cast<int>(*std::max_element(indices, end)) + 1 : 0);
      Decorations decorations;
      decorations.box = vertex_box(list, static_cast<int>(first.VtxOffset), last, width, height);
      if (overlap(decorations.box, *under.drawn)) return std::nullopt;
      append_bytes(decorations.key, list.VtxBuffer.Data + first.VtxOffset,
                   static_cast<std::size_t>(last) - first.VtxOffset);
      append_bytes(decorations.key, indices, first.ElemCount);
      append_bytes(decorations.key, &first.ClipRect, 1);
      append_bytes(decorations.key, &first.TextureId, 1);
      const int size[2] = {width, height};
      append_bytes(decorations.key, size, 2);
      found.push_back(std::move(decorations));
    }
    lists.push_back(whole);
  }
  return found;
}

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
  stored_.clear();  // the atlas's texture may come back under the same name
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

void OverlayPass::lay_out(const DrawList& frame, int width, int height) {
  ensure_fonts(frame, width, height);
  // ImGui sizes an auto-fitting window one frame after it first appears: lay out a hidden
  // frame first whenever a panel is new, so that its first image already shows it.
  bool new_panel = false;
  for (int i = 0; i < static_cast<int>(frame.panels.size()); ++i) {
    new_panel |= known_panels_.insert(panel_id(frame.panels[i], i)).second;
  }
  if (new_panel) build(frame, width, height);
  build(frame, width, height);
}

void OverlayPass::draw(const DrawList& frame, int width, int height) {
  ContextGuard guard(context_);
  lay_out(frame, width, height);
  last_boxes_ = draw_data_boxes(*ImGui::GetDrawData(), width, height);
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

void OverlayPass::draw(const DrawList& frame, int width, int height, OffscreenContext& context,
                       const OverlayUnder& under) {
  ContextGuard guard(context_);
  lay_out(frame, width, height);
  ImDrawData& data = *ImGui::GetDrawData();
  last_boxes_ = draw_data_boxes(data, width, height);
  std::optional<std::vector<Decorations>> now = decorations(data, width, height, under);
  if (!now || now->empty()) {
    stored_.clear();
    ImGui_ImplOpenGL3_RenderDrawData(&data);
    return;
  }
  const auto decoration = [&](int l, int c) {
    return c == 0 && has_decorations(*data.CmdLists[l]);
  };
  const auto same = [](const Decorations& a, const Decorations& b) { return a.key == b.key; };
  const bool reuse = under.layers == stored_layers_ && context.has_stored_output() &&
                     std::equal(now->begin(), now->end(), stored_.begin(), stored_.end(), same);
  if (reuse) {
    for (const Decorations& d : *now)
      context.restore_output_box(d.box.x0, d.box.y0, d.box.x1, d.box.y1);
  } else {
    render_commands(data, decoration);
    bool stored = true;
    for (const Decorations& d : *now) {
      stored = stored && context.store_output_box(d.box.x0, d.box.y0, d.box.x1, d.box.y1);
    }
    stored_ = stored ? std::move(*now) : std::vector<Decorations>{};
    stored_layers_ = under.layers;
  }
  render_commands(data, [&](int l, int c) { return !decoration(l, c); });
}

}  // namespace tumble::render::detail
