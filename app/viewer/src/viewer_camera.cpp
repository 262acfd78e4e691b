// The viewer's orbit camera: spherical coordinates about a target, driven by drag and wheel.
#include "app/viewer/viewer_camera.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace tumble::app::viewer {
namespace {

double to_radians(double deg) {
  return deg * std::numbers::pi / 180.0;
}
double to_degrees(double rad) {
  return rad * 180.0 / std::numbers::pi;
}

/// The zoom range around the starting distance.
constexpr double kMinDistanceFactor = 1e-3;
constexpr double kMaxDistanceFactor = 1e3;

}  // namespace

OrbitCamera::OrbitCamera(const render::Camera& camera)
    : target_(camera.target.cast<double>()), fov_deg_(camera.vertical_fov_deg) {
  // Spherical coordinates of eye - target; a degenerate offset keeps the default direction.
  const Eigen::Vector3d offset = camera.eye.cast<double>() - target_;
  const double length = offset.norm();
  if (std::isfinite(length) && length > 0.0) {
    distance_ = length;
    azimuth_deg_ = to_degrees(std::atan2(offset.y(), offset.x()));
    elevation_deg_ = std::clamp(to_degrees(std::asin(std::clamp(offset.z() / length, -1.0, 1.0))),
                                -kMaxElevation, kMaxElevation);
  }
  min_distance_ = kMinDistanceFactor * distance_;
  max_distance_ = kMaxDistanceFactor * distance_;
}

bool OrbitCamera::handle(const InputEvent& event, bool imgui_wants_mouse) {
  // Left button: a press outside ImGui starts a drag; the release ends it (moving to its spot).
  if (const auto* button = std::get_if<MouseButtonEvent>(&event)) {
    if (button->button != 0) return false;
    if (button->down) {
      if (imgui_wants_mouse) return false;
      dragging_ = true;
      last_x_ = button->x;
      last_y_ = button->y;
      return false;
    }
    if (!dragging_) return false;
    const bool moved = button->x != last_x_ || button->y != last_y_;
    orbit(button->x - last_x_, button->y - last_y_);
    dragging_ = false;
    return moved;
  }
  // Moves orbit while dragging, over panels too.
  if (const auto* move = std::get_if<MouseMoveEvent>(&event)) {
    if (!dragging_) return false;
    const bool moved = move->x != last_x_ || move->y != last_y_;
    orbit(move->x - last_x_, move->y - last_y_);
    last_x_ = move->x;
    last_y_ = move->y;
    return moved;
  }
  // The wheel zooms unless ImGui scrolls a panel with it.
  if (const auto* wheel = std::get_if<WheelEvent>(&event)) {
    if (imgui_wants_mouse || wheel->dy == 0.0f) return false;
    const double before = distance_;
    zoom(wheel->dy);
    return distance_ != before;
  }
  return false;
}

void OrbitCamera::zoom(double notches) {
  distance_ =
      std::clamp(distance_ * std::pow(kZoomPerNotch, -notches), min_distance_, max_distance_);
}

void OrbitCamera::orbit(double dx_px, double dy_px) {
  // Azimuth wraps to [-180, 180); elevation stops short of the poles.
  azimuth_deg_ = std::remainder(azimuth_deg_ - kDegreesPerPixel * dx_px, 360.0);
  if (azimuth_deg_ >= 180.0) azimuth_deg_ -= 360.0;
  elevation_deg_ =
      std::clamp(elevation_deg_ + kDegreesPerPixel * dy_px, -kMaxElevation, kMaxElevation);
}

Eigen::Vector3d OrbitCamera::eye() const {
  const double az = to_radians(azimuth_deg_);
  const double el = to_radians(elevation_deg_);
  return target_ + distance_ * Eigen::Vector3d(std::cos(el) * std::cos(az),
                                               std::cos(el) * std::sin(az), std::sin(el));
}

render::Camera OrbitCamera::camera(double reach) const {
  render::Camera out;
  out.eye = eye().cast<float>();
  out.target = target_.cast<float>();
  out.up = Eigen::Vector3f::UnitZ();
  out.vertical_fov_deg = static_cast<float>(fov_deg_);
  // Near plane as far out as the reach sphere allows (depth precision); far plane past it.
  out.near_plane = static_cast<float>(std::max(2e-3 * distance_, 0.5 * (distance_ - 1.5 * reach)));
  out.far_plane = static_cast<float>(8.0 * (distance_ + reach));
  return out;
}

}  // namespace tumble::app::viewer
