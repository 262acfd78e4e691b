#pragma once
// Text labels and HUD panels (title, text lines, line plots) drawn with Dear ImGui's OpenGL3
// backend on top of the 3D passes. Created lazily: only frames with labels or panels pay for it.

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <unordered_set>
#include <vector>

#include "fxaa_blocks.hpp"
#include "render/draw_list.hpp"

struct ImGuiContext;
struct ImFont;
struct ImGuiStyle;
struct ImDrawData;

namespace tumble::render {
class OffscreenContext;
}

namespace tumble::render::detail {

/// What lies under the overlay in the output framebuffer: the stored static layers of
/// generation `layers` (0: not known to be), drawn over by the scene only within `drawn` (GL's
/// pixel coordinates; empty: possibly anywhere).
struct OverlayUnder {
  std::uint64_t layers = 0;
  std::optional<PixelBox> drawn;
};

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
  /// The same into `context`'s output, reusing what stays: a panel's decorations (its first
  /// draw command: background, title bar and title, drawn before its lines and plots) over the
  /// stored layers `under` says lie beneath them are drawn once, their pixels stored, and
  /// restored by a memory copy while neither they nor what lies under them change. The image
  /// is the same pixel for pixel (tests/render/static_layers_test.cpp).
  void draw(const DrawList& frame, int width, int height, OffscreenContext& context,
            const OverlayUnder& under);
  /// Where the last draw drew: a box per ImGui draw list, that is per window (GL's pixel
  /// coordinates, a pixel of margin).
  /// Not one box round them all: on the default demo, its panel and a small window far apart
  /// spanned 346,000 pixels, and the two boxes hold 75,000.
  const std::vector<PixelBox>& last_boxes() const { return last_boxes_; }

 private:
  void build(const DrawList& frame, int width, int height);
  void draw_labels(const DrawList& frame, int width, int height);
  /// Adds the fonts the frame needs to the atlas (rebuilt and re-uploaded only when a size is
  /// new); must run outside an ImGui frame.
  void ensure_fonts(const DrawList& frame, int width, int height);
  ImFont* font(float font_px) const;
  static std::string panel_id(const OverlayPanel& panel, int index);
  /// Lays out the frame (twice when a panel is new, so that it is sized from the first image).
  void lay_out(const DrawList& frame, int width, int height);

  /// A window's decorations this frame: what their pixels depend on, and where they lie.
  struct Decorations {
    std::vector<unsigned char> key;  // vertices, indices, clip rectangle, texture, frame size
    PixelBox box;                    // GL's pixel coordinates, one pixel of margin
  };
  /// The decorations of every window of `data` that may be stored (see draw), or nothing when
  /// the split into decorations first and the rest after would change the image.
  static std::optional<std::vector<Decorations>> decorations(const ImDrawData& data, int width,
                                                             int height, const OverlayUnder& under);

  ImGuiContext* context_ = nullptr;
  std::map<int, ImFont*> fonts_;  // ImGui's default font rasterised at each pixel size in use
  std::unique_ptr<ImGuiStyle> base_style_;        // the style at 13 px, scaled per panel
  std::unordered_set<std::string> known_panels_;  // ImGui window ids laid out so far
  std::vector<Decorations> stored_;               // held by the context's stored output boxes
  std::uint64_t stored_layers_ = 0;               // over these static layers
  std::vector<PixelBox> last_boxes_;              // last_boxes()
};

}  // namespace tumble::render::detail
