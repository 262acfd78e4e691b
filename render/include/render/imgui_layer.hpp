#pragma once
// An interactive Dear ImGui layer drawn over a Renderer's frames (the viewer's panels): an ImGui
// context of its own, separate from the overlay pass's, with the OpenGL3 backend initialised in
// the renderer's GL context. The caller feeds its input (ImGuiIO of context()) and builds its
// widgets in the callback given to pass().

#include <functional>

#include "render/image.hpp"
#include "render/renderer.hpp"

struct ImGuiContext;

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

  /// A pass for Renderer::render: one ImGui frame of `delta_seconds` over the frame, with
  /// `build` called between ImGui::NewFrame() and ImGui::Render(), then `after_new_frame` hooks
  /// (input latches) run right after NewFrame. `before` receives the frame without the layer.
  ExtraPass pass(float delta_seconds, std::function<void()> build,
                 std::function<void()> after_new_frame = {}, Image* before = nullptr);

 private:
  Renderer& renderer_;
  ImGuiContext* context_ = nullptr;
};

}  // namespace tumble::render
