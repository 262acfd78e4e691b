#pragma once
/// @file The viewer's camera: orbit by dragging, zoom by the wheel, optionally following a body.
/// Mouse input reaches it only when ImGui does not want the mouse (the pointer is not over a
/// panel and no widget is being dragged).

#include <Eigen/Core>

#include "app/viewer/viewer_input.hpp"
#include "render/draw_list.hpp"

namespace tumble::app::viewer {

/// A camera on a sphere around a target: azimuth about world z from +x, elevation above the
/// xy plane, distance from the target. Drag (left button) orbits; the wheel zooms.
class OrbitCamera {
 public:
  /// Degrees of orbit per pixel of drag.
  static constexpr double kDegreesPerPixel = 0.3;
  /// Distance factor per wheel notch (in: divide, out: multiply).
  static constexpr double kZoomPerNotch = 1.15;
  /// Elevation stays within +-kMaxElevation degrees (the view never flips over the pole).
  static constexpr double kMaxElevation = 89.0;

  OrbitCamera() = default;
  /// Takes eye, target and field of view from `camera` (a frame of `tumble render`, so the
  /// viewer starts where a render would).
  explicit OrbitCamera(const render::Camera& camera);

  /// Feeds one event. `imgui_wants_mouse` is io.WantCaptureMouse: when set, presses are not
  /// taken (a drag that started outside a panel keeps going over one). Returns true when the
  /// camera moved.
  bool handle(const InputEvent& event, bool imgui_wants_mouse);

  /// Zooms by `notches` (positive: closer). Distance is clamped to [min, max] distance.
  void zoom(double notches);
  /// Orbits by a drag of (dx, dy) pixels: right drag turns the view to the right (azimuth
  /// decreases), down drag raises the eye (elevation increases).
  void orbit(double dx_px, double dy_px);

  void set_target(const Eigen::Vector3d& target) { target_ = target; }
  const Eigen::Vector3d& target() const { return target_; }
  double distance() const { return distance_; }
  double azimuth_deg() const { return azimuth_deg_; }
  double elevation_deg() const { return elevation_deg_; }
  Eigen::Vector3d eye() const;
  bool dragging() const { return dragging_; }

  /// The renderer's camera: eye, target, up +z, field of view; near and far planes from the
  /// distance and `reach` (radius around the target that must stay visible, m).
  render::Camera camera(double reach) const;

 private:
  Eigen::Vector3d target_ = Eigen::Vector3d::Zero();
  double distance_ = 5.0;
  double azimuth_deg_ = -60.0;
  double elevation_deg_ = 25.0;
  double fov_deg_ = 40.0;
  double min_distance_ = 1e-3;
  double max_distance_ = 1e4;
  bool dragging_ = false;
  float last_x_ = 0.0f;
  float last_y_ = 0.0f;
};

}  // namespace tumble::app::viewer
