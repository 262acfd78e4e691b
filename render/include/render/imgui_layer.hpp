#pragma once
// An interactive Dear ImGui layer drawn over a Renderer's frames (the viewer's panels): an ImGui
// context of its own, separate from the overlay pass's, with the OpenGL3 backend initialised in
// the renderer's GL context. The caller feeds its input (ImGuiIO of context()) and builds its
// widgets in the callback given to pass().

#include <functional>
#include <memory>

#include "base/image.hpp"
#include "render/renderer.hpp"

struct ImGuiContext;
struct ImGuiStyle;

namespace tumble::render {

class ImGuiLayer {
 public:
  /// Creates the context and the backend's GL objects in `renderer`'s context (which must
  /// outlive the layer), and makes the new context current. Throws std::runtime_error (one
  /// line) when the backend cannot start.
  explicit ImGuiLayer(Renderer& renderer);
  ~ImGuiLayer();
  ImGuiLayer(const ImGuiLayer&) = delete;
  ImGuiLayer& operator=(const ImGuiLayer&) = delete;

  ImGuiContext* context() const { return context_; }

  /// Text height of the next passes, in pixels (13 at first): the default font rasterised at
  /// that size (not a scaled bitmap) and every spacing of the style scaled by px / 13, as the
  /// render overlay does. Takes effect at the next pass's frame (the font atlas is rebuilt
  /// there, before ImGui::NewFrame); rounded to whole pixels within [kMinFontPx, kMaxFontPx].
  void set_font_px(float px);
  /// The text height the passes use now.
  float font_px() const { return font_px_; }

  /// A pass for Renderer::render: one ImGui frame of `delta_seconds` over the frame, with
  /// `build` called between ImGui::NewFrame() and ImGui::Render(), then `after_new_frame` hooks
  /// (input latches) run right after NewFrame. `before` receives the frame without the layer.
  ExtraPass pass(float delta_seconds, std::function<void()> build,
                 std::function<void()> after_new_frame = {}, Image* before = nullptr);

 private:
  /// Rebuilds the font atlas at wanted_px_ and scales the style (GL context current).
  void apply_font_size();

  Renderer& renderer_;
  ImGuiContext* context_ = nullptr;
  std::unique_ptr<ImGuiStyle> base_style_;
  float font_px_ = 13.0f;    ///< of the atlas
  float wanted_px_ = 13.0f;  ///< for the next frame
};

}  // namespace tumble::render
