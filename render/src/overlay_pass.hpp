#pragma once
// Text labels and HUD panels (title, text lines, line plots) drawn with Dear ImGui's OpenGL3
// backend on top of the 3D passes. Created lazily: only frames with labels or panels pay for it.

#include <map>
#include <memory>
#include <string>
#include <unordered_set>

#include "render/draw_list.hpp"

struct ImGuiContext;
struct ImFont;
struct ImGuiStyle;

namespace tumble::render::detail {

class OverlayPass {
 public:
  /// Creates an ImGui context of its own and the GL objects (font atlas built once); needs the
  /// GL context current.
  OverlayPass();
  ~OverlayPass();
  OverlayPass(const OverlayPass&) = delete;
  OverlayPass& operator=(const OverlayPass&) = delete;

  /// Draws the frame's labels and panels over the currently bound framebuffer.
  void draw(const DrawList& frame, int width, int height);

 private:
  void build(const DrawList& frame, int width, int height);
  void draw_labels(const DrawList& frame, int width, int height);
  /// Adds the fonts the frame needs to the atlas (rebuilt and re-uploaded only when a size is
  /// new); must run outside an ImGui frame.
  void ensure_fonts(const DrawList& frame, int width, int height);
  ImFont* font(float font_px) const;
  static std::string panel_id(const OverlayPanel& panel, int index);

  ImGuiContext* context_ = nullptr;
  std::map<int, ImFont*> fonts_;  // ImGui's default font rasterised at each pixel size in use
  std::unique_ptr<ImGuiStyle> base_style_;        // the style at 13 px, scaled per panel
  std::unordered_set<std::string> known_panels_;  // ImGui window ids laid out so far
};

}  // namespace tumble::render::detail
