// The anti-aliasing filter reads back and scans only the box where anything but the background
// was drawn: its frames against the same frames scanned whole, pixel for pixel, over bodies
// moving across the frame and out of it, lines, points, a translucent body, a camera inside a
// body's bounds, an empty frame and a frame size that is not a multiple of the blocks.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <vector>

#include "render/renderer.hpp"
#include "render_support.hpp"

namespace tumble::render {
namespace {

using testing::box_mesh;

/// Frame `i`: a box crossing the frame from left to right (out of it at both ends), a
/// translucent box, an arrow, and a trail and a point away from them (top right, top left); frame
/// 13 puts the camera inside the body's bounding sphere, frame 14 draws nothing.
DrawList crossing_frame(MeshId box, int i) {
  DrawList frame;
  frame.camera.eye = {3.0f, -4.0f, 2.5f};
  frame.camera.target = {0.0f, 0.0f, 0.3f};
  frame.style.ground = false;
  if (i == 14) return frame;
  const float x = -4.0f + 0.6f * static_cast<float>(i);
  const float angle = 0.35f * static_cast<float>(i);
  testing::add_run_solids(frame, box, {x, 0.5f * x, 0.2f}, angle);
  Polyline trail;
  trail.width_px = 3.0f;
  for (int k = 0; k <= i; ++k) {
    trail.points.emplace_back(1.2f + 0.05f * static_cast<float>(k), -1.0f,
                              1.2f + 0.05f * static_cast<float>(k));
  }
  frame.polylines.push_back(trail);
  frame.points.push_back({{Eigen::Vector3f(-1.0f, -1.5f, 1.6f)}, {1.0f, 1.0f, 0.0f, 1.0f}, 6.0f});
  if (i == 13) frame.camera.eye = {x + 0.05f, 0.5f * x, 0.2f};  // inside the box
  return frame;
}

TEST(FxaaRegion, FramesEqualThoseScannedWhole) {
  for (const auto& [width, height] : {std::pair{200, 150}, std::pair{203, 151}}) {
    RendererOptions options{width, height};
    options.filter = AntialiasingFilter::fxaa;
    RendererOptions whole_options = options;
    whole_options.filter_drawn_region = false;
    RendererOptions aliased_options = options;
    aliased_options.filter = AntialiasingFilter::none;
    Renderer region(options);
    Renderer whole(whole_options);
    Renderer aliased(aliased_options);
    const MeshData mesh = box_mesh({0.5f, 0.4f, 0.3f});
    const MeshId a_box = region.upload(mesh);
    const MeshId b_box = whole.upload(mesh);
    const MeshId c_box = aliased.upload(mesh);
    std::size_t filtered_frames = 0;
    for (int i = 0; i <= 14; ++i) {
      SCOPED_TRACE(::testing::Message() << width << "x" << height << " frame " << i);
      const Image a = region.render(crossing_frame(a_box, i));
      const Image b = whole.render(crossing_frame(b_box, i));
      const Image c = aliased.render(crossing_frame(c_box, i));
      ASSERT_EQ(a.rgba.size(), b.rgba.size());
      std::size_t differing = 0;
      for (std::size_t k = 0; k < a.rgba.size(); ++k) differing += a.rgba[k] != b.rgba[k];
      EXPECT_EQ(differing, 0u);
      // Not vacuous: the filter changed the frame wherever something with edges was drawn.
      filtered_frames += a.rgba != c.rgba;
    }
    EXPECT_GE(filtered_frames, 12u);
  }
}

}  // namespace
}  // namespace tumble::render
