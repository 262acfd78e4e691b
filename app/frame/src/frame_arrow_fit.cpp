// Arrows kept inside the image: one common shrink factor for a frame's arrows, found by
// bisection on their projected tips.
#include <algorithm>

#include "frame_builder_impl.hpp"
#include "render/camera_math.hpp"

namespace tumble::app::detail {
namespace {

bool inside(const render::Camera& camera, int width, int height, float margin,
            const Eigen::Vector3f& world) {
  const Eigen::Vector3f p = render::project_to_pixels(camera, width, height, world);
  return p.z() > 0.0f && p.x() >= margin && p.y() >= margin &&
         p.x() <= static_cast<float>(width) - margin &&
         p.y() <= static_cast<float>(height) - margin;
}

}  // namespace

double keep_arrows_inside(render::DrawList& list, int width, int height, float margin) {
  double factor = 1.0;
  for (const render::Arrow& arrow : list.arrows) {
    if (!inside(list.camera, width, height, margin, arrow.from)) continue;
    if (inside(list.camera, width, height, margin, arrow.to)) continue;
    double low = 0.0;
    double high = 1.0;
    for (int k = 0; k < 30; ++k) {
      const double mid = 0.5 * (low + high);
      const Eigen::Vector3f tip = arrow.from + static_cast<float>(mid) * (arrow.to - arrow.from);
      (inside(list.camera, width, height, margin, tip) ? low : high) = mid;
    }
    factor = std::min(factor, low);
  }
  if (factor >= 1.0) return 1.0;
  const float f = static_cast<float>(factor);
  for (render::Arrow& arrow : list.arrows) {
    const Eigen::Vector3f tip = arrow.from + f * (arrow.to - arrow.from);
    for (render::Label& label : list.labels) {
      if (label.anchor && *label.anchor == arrow.to) label.anchor = tip;
    }
    arrow.to = tip;
  }
  return factor;
}

}  // namespace tumble::app::detail
