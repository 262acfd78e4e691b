#pragma once
/// @file What the files of the viewer's panels (viewer_panels*.cpp) share: colours and widgets.

#include <imgui.h>

#include <cstddef>
#include <vector>

#include "engine/body/rigid_body.hpp"
#include "render/overlay_layout.hpp"

namespace tumble::app::viewer {

inline const ImVec4 kErrorColour{1.0f, 0.45f, 0.40f, 1.0f};
inline const ImVec4 kDimColour{0.70f, 0.70f, 0.70f, 1.0f};

/// `px` pixels of a layout made for 13 px text, at the current font's size (the panels' sizes
/// follow the text, as the render overlay's do).
inline float scaled(float px) {
  return px * ImGui::GetFontSize() / render::kDefaultFontPx;
}

/// A combo box `width` pixels wide listing the bodies by name; a click sets `chosen`.
void body_combo(const char* label, float width, const std::vector<engine::BodyModel>& bodies,
                std::size_t& chosen);

}  // namespace tumble::app::viewer
