// The layers of a frame that stay while the camera stays: the background gradient and the
// ground outside the shadow's patch. They are drawn once into the scene FBO, stored (colour and
// depth) and, while the frame's key is unchanged, restored at the start of each later frame by
// a plain memory copy, which costs less than shading them again on llvmpipe. They are stored
// on the second frame with the same key, so a camera that moves every frame stores nothing.
// Everything that moves (solids, the shadowed patch, lines, points, translucent solids) is drawn on
// top as before; because solids are opaque and the stored depth is what the ground and the
// background would have left, the image is the same pixel for pixel
// (tests/render/static_layers_test.cpp).
#include <Eigen/Core>
#include <initializer_list>
#include <optional>
#include <utility>

#include "scene_passes.hpp"

namespace tumble::render::detail {

namespace {

void append_static_key(std::vector<float>& key, const Eigen::Vector3f& v) {
  key.insert(key.end(), {v.x(), v.y(), v.z()});
}

void append_static_key(std::vector<float>& key, const Rgba& c) {
  key.insert(key.end(), {c.r, c.g, c.b, c.a});
}

}  // namespace

bool ScenePasses::static_layers(const DrawList& frame, const GroundPlacement& ground,
                                OffscreenContext& context) {
  const SceneStyle& style = frame.style;
  // Where the last frame drew over the layers (if it started from them); until this frame
  // does, nothing is known.
  const std::optional<PixelBox> written = std::exchange(written_, std::nullopt);
  frame_layers_ = 0;
  // A ground shadowed all over (a grazing light) changes with every frame.
  if (!reuse_static_layers_ || (style.ground && shadow_valid_ && !ground.patch)) return false;

  // Everything the two layers' pixels and depths depend on, compared bit for bit.
  static_key_.clear();
  static_key_.insert(static_key_.end(), view_projection_.data(), view_projection_.data() + 16);
  static_key_.insert(static_key_.end(),
                     {static_cast<float>(context.width()), static_cast<float>(context.height())});
  append_static_key(static_key_, style.background_top);
  append_static_key(static_key_, style.background_bottom);
  static_key_.push_back(style.ground ? 1.0f : 0.0f);
  if (style.ground) {
    append_static_key(static_key_, ground.centre);
    append_static_key(static_key_, ground.axis_u);
    append_static_key(static_key_, ground.axis_v);
    static_key_.push_back(ground.half_size);
    static_key_.push_back(ground.patch ? 1.0f : 0.0f);  // the polygon offset
    append_static_key(static_key_, style.ground_normal);
    append_static_key(static_key_, style.key_light_from);
    append_static_key(static_key_, style.ground_colour);
  }

  if (static_key_ == stored_static_key_ && context.has_stored_scene()) {
    if (written && !style.ground) {
      // Only the last frame's drawn box differs from the stored layers, in colour and depth
      // (their depth is the cleared one: the background writes none).
      context.restore_scene_box(written->x0, written->y0, written->x1, written->y1);
    } else {
      context.restore_scene(/*depth=*/style.ground);  // the background writes no depth
    }
    written_ = drawn_;
    frame_layers_ = layers_generation_;
    return true;
  }
  // Stored only when a frame repeats the last one's key: a camera that moves every frame would
  // pay for a copy it never uses.
  const bool repeated = static_key_ == last_static_key_;
  last_static_key_ = static_key_;
  if (!repeated) return false;

  glClear(GL_DEPTH_BUFFER_BIT);
  if (style.ground) draw_ground_part(frame, ground, 1, context.height());
  draw_background(style);
  if (!context.store_scene()) {
    reuse_static_layers_ = false;  // no memory for the copy: draw every layer from now on
    stored_static_key_.clear();
    return false;
  }
  stored_static_key_ = static_key_;
  written_ = drawn_;
  frame_layers_ = ++layers_generation_;
  return true;
}

}  // namespace tumble::render::detail
