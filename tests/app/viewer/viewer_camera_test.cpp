#include "app/viewer/viewer_camera.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace tumble::app::viewer {
namespace {

constexpr double kCameraDeg = std::numbers::pi / 180.0;

/// target + distance * (cos el cos az, cos el sin az, sin el), the orbit's closed form.
Eigen::Vector3d sphere_point(const Eigen::Vector3d& target, double distance, double az_deg,
                             double el_deg) {
  const double az = az_deg * kCameraDeg;
  const double el = el_deg * kCameraDeg;
  return target + distance * Eigen::Vector3d(std::cos(el) * std::cos(az),
                                             std::cos(el) * std::sin(az), std::sin(el));
}

/// A render camera at distance 10 from (1, 2, 3), azimuth 30 degrees, elevation 20 degrees.
render::Camera render_camera() {
  render::Camera camera;
  camera.target = Eigen::Vector3f(1.0f, 2.0f, 3.0f);
  camera.eye = sphere_point(Eigen::Vector3d(1, 2, 3), 10.0, 30.0, 20.0).cast<float>();
  camera.vertical_fov_deg = 35.0f;
  return camera;
}

void expect_near(const Eigen::Vector3d& actual, const Eigen::Vector3d& expected, double tol) {
  EXPECT_NEAR(actual.x(), expected.x(), tol);
  EXPECT_NEAR(actual.y(), expected.y(), tol);
  EXPECT_NEAR(actual.z(), expected.z(), tol);
}

MouseButtonEvent left(bool down, float x, float y) {
  return {0, down, x, y};
}

TEST(ViewerCamera, DefaultEyeIsOnTheDefaultSphere) {
  const OrbitCamera camera;
  EXPECT_EQ(camera.distance(), 5.0);
  EXPECT_EQ(camera.azimuth_deg(), -60.0);
  EXPECT_EQ(camera.elevation_deg(), 25.0);
  expect_near(camera.eye(), sphere_point(Eigen::Vector3d::Zero(), 5.0, -60.0, 25.0), 1e-12);
  // Explicitly: 5 (cos 25 cos(-60), cos 25 sin(-60), sin 25).
  expect_near(camera.eye(), Eigen::Vector3d(2.2657695, -3.9244278, 2.1130913), 1e-6);
}

TEST(ViewerCamera, TakesSphericalCoordinatesFromARenderCamera) {
  const OrbitCamera camera(render_camera());
  EXPECT_NEAR(camera.distance(), 10.0, 1e-5);
  EXPECT_NEAR(camera.azimuth_deg(), 30.0, 1e-4);
  EXPECT_NEAR(camera.elevation_deg(), 20.0, 1e-4);
  expect_near(camera.target(), Eigen::Vector3d(1, 2, 3), 0.0);
  expect_near(camera.eye(), render_camera().eye.cast<double>(), 1e-5);
}

TEST(ViewerCamera, RenderCameraRoundTrip) {
  const render::Camera original = render_camera();
  const render::Camera back = OrbitCamera(original).camera(1.0);
  EXPECT_TRUE(back.eye.isApprox(original.eye, 1e-6f));
  EXPECT_EQ(back.target, original.target);
  EXPECT_EQ(back.up, Eigen::Vector3f::UnitZ());
  EXPECT_EQ(back.vertical_fov_deg, 35.0f);
}

TEST(ViewerCamera, EyeStraightAboveIsClampedBelowThePole) {
  render::Camera top;
  top.target = Eigen::Vector3f::Zero();
  top.eye = Eigen::Vector3f(0.0f, 0.0f, 4.0f);
  const OrbitCamera camera(top);
  EXPECT_NEAR(camera.distance(), 4.0, 1e-12);
  EXPECT_EQ(camera.elevation_deg(), 89.0);
}

TEST(ViewerCamera, NearAndFarPlanesFollowDistanceAndReach) {
  const OrbitCamera camera(render_camera());  // distance 10
  // Reach 1: near = max(0.02, 0.5 (10 - 1.5)) = 4.25, far = 8 (10 + 1) = 88.
  const render::Camera tight = camera.camera(1.0);
  EXPECT_NEAR(tight.near_plane, 4.25f, 1e-5f);
  EXPECT_NEAR(tight.far_plane, 88.0f, 1e-4f);
  // Reach 10 encloses the eye: near falls back to 2e-3 of the distance.
  const render::Camera wide = camera.camera(10.0);
  EXPECT_NEAR(wide.near_plane, 0.02f, 1e-7f);
  EXPECT_NEAR(wide.far_plane, 160.0f, 1e-4f);
}

TEST(ViewerCamera, OrbitTurnsByDegreesPerPixel) {
  OrbitCamera camera;
  camera.orbit(100.0, 50.0);  // right 100 px: azimuth -30; down 50 px: elevation +15
  EXPECT_NEAR(camera.azimuth_deg(), -90.0, 1e-12);
  EXPECT_NEAR(camera.elevation_deg(), 40.0, 1e-12);
  EXPECT_EQ(camera.distance(), 5.0);
  expect_near(camera.eye(), sphere_point(Eigen::Vector3d::Zero(), 5.0, -90.0, 40.0), 1e-12);
}

TEST(ViewerCamera, AzimuthWrapsIntoOneTurn) {
  OrbitCamera camera;
  camera.orbit(-900.0, 0.0);  // -60 + 270 = 210 = -150
  EXPECT_NEAR(camera.azimuth_deg(), -150.0, 1e-9);
  camera.orbit(-100.0, 0.0);  // -150 + 30 = -120
  EXPECT_NEAR(camera.azimuth_deg(), -120.0, 1e-9);
}

TEST(ViewerCamera, ElevationStopsAtTheClamp) {
  OrbitCamera camera;
  camera.orbit(0.0, 1000.0);
  EXPECT_EQ(camera.elevation_deg(), 89.0);
  camera.orbit(0.0, -10000.0);
  EXPECT_EQ(camera.elevation_deg(), -89.0);
}

TEST(ViewerCamera, ZoomDividesByTheFactorPerNotch) {
  OrbitCamera camera(render_camera());
  const double d = camera.distance();
  camera.zoom(1.0);
  EXPECT_NEAR(camera.distance(), d / 1.15, 1e-12);
  camera.zoom(-3.0);
  EXPECT_NEAR(camera.distance(), d * 1.15 * 1.15, 1e-12);
  // Zoom keeps direction: the eye stays on the same ray from the target.
  expect_near(camera.eye(), sphere_point(camera.target(), d * 1.15 * 1.15, 30.0, 20.0), 1e-4);
}

TEST(ViewerCamera, ZoomIsClampedAroundTheStartingDistance) {
  OrbitCamera camera(render_camera());
  const double d = camera.distance();
  camera.zoom(1000.0);
  EXPECT_NEAR(camera.distance(), 1e-3 * d, 1e-12);
  camera.zoom(-5000.0);
  EXPECT_NEAR(camera.distance(), 1e3 * d, 1e-9);
}

TEST(ViewerCamera, LeftDragOrbitsByTheMovedPixels) {
  OrbitCamera camera;
  EXPECT_FALSE(camera.handle(left(true, 200.0f, 100.0f), false));
  EXPECT_TRUE(camera.dragging());
  EXPECT_TRUE(camera.handle(MouseMoveEvent{250.0f, 110.0f}, false));
  EXPECT_TRUE(camera.handle(MouseMoveEvent{300.0f, 150.0f}, false));
  // 100 px right and 50 px down in all.
  EXPECT_NEAR(camera.azimuth_deg(), -90.0, 1e-5);
  EXPECT_NEAR(camera.elevation_deg(), 40.0, 1e-5);
  // Releasing on the spot ends the drag without moving; later moves do nothing.
  EXPECT_FALSE(camera.handle(left(false, 300.0f, 150.0f), false));
  EXPECT_FALSE(camera.dragging());
  EXPECT_FALSE(camera.handle(MouseMoveEvent{0.0f, 0.0f}, false));
  EXPECT_NEAR(camera.azimuth_deg(), -90.0, 1e-5);
}

TEST(ViewerCamera, ReleaseAtAnotherSpotOrbitsThere) {
  OrbitCamera camera;
  camera.handle(left(true, 0.0f, 0.0f), false);
  EXPECT_TRUE(camera.handle(left(false, -10.0f, 0.0f), false));  // 10 px left: azimuth +3
  EXPECT_NEAR(camera.azimuth_deg(), -57.0, 1e-5);
  EXPECT_FALSE(camera.dragging());
}

TEST(ViewerCamera, PressOverAPanelStartsNoDrag) {
  OrbitCamera camera;
  EXPECT_FALSE(camera.handle(left(true, 10.0f, 10.0f), true));
  EXPECT_FALSE(camera.dragging());
  EXPECT_FALSE(camera.handle(MouseMoveEvent{200.0f, 200.0f}, false));
  EXPECT_EQ(camera.azimuth_deg(), -60.0);
  EXPECT_EQ(camera.elevation_deg(), 25.0);
}

TEST(ViewerCamera, DragStartedOutsideContinuesOverAPanel) {
  OrbitCamera camera;
  camera.handle(left(true, 10.0f, 10.0f), false);
  EXPECT_TRUE(camera.handle(MouseMoveEvent{10.0f, 30.0f}, true));  // 20 px down: +6 degrees
  EXPECT_NEAR(camera.elevation_deg(), 31.0, 1e-5);
}

TEST(ViewerCamera, OnlyTheLeftButtonDrags) {
  OrbitCamera camera;
  EXPECT_FALSE(camera.handle(MouseButtonEvent{1, true, 0.0f, 0.0f}, false));
  EXPECT_FALSE(camera.handle(MouseButtonEvent{2, true, 0.0f, 0.0f}, false));
  EXPECT_FALSE(camera.dragging());
  EXPECT_FALSE(camera.handle(MouseMoveEvent{50.0f, 50.0f}, false));
  EXPECT_EQ(camera.azimuth_deg(), -60.0);
}

TEST(ViewerCamera, WheelZoomsUnlessImGuiWantsTheMouse) {
  OrbitCamera camera;
  EXPECT_TRUE(camera.handle(WheelEvent{2.0f}, false));
  EXPECT_NEAR(camera.distance(), 5.0 / (1.15 * 1.15), 1e-12);
  EXPECT_FALSE(camera.handle(WheelEvent{-1.0f}, true));
  EXPECT_NEAR(camera.distance(), 5.0 / (1.15 * 1.15), 1e-12);
  EXPECT_TRUE(camera.handle(WheelEvent{-0.5f}, false));  // smooth wheels give fractions
  EXPECT_NEAR(camera.distance(), 5.0 / std::pow(1.15, 1.5), 1e-12);
}

TEST(ViewerCamera, WheelAtTheClampReportsNoMove) {
  OrbitCamera camera(render_camera());
  camera.zoom(1000.0);
  EXPECT_FALSE(camera.handle(WheelEvent{1.0f}, false));
  EXPECT_TRUE(camera.handle(WheelEvent{-1.0f}, false));
}

TEST(ViewerCamera, OtherEventsLeaveTheCamera) {
  OrbitCamera camera;
  EXPECT_FALSE(camera.handle(KeyEvent{Key::kLeft, true, {}}, false));
  EXPECT_FALSE(camera.handle(TextEvent{"w"}, false));
  EXPECT_FALSE(camera.handle(QuitEvent{}, false));
  EXPECT_EQ(camera.distance(), 5.0);
  EXPECT_EQ(camera.azimuth_deg(), -60.0);
}

TEST(ViewerCamera, FollowingATargetMovesTheEyeWithIt) {
  OrbitCamera camera;
  const Eigen::Vector3d before = camera.eye();
  camera.set_target(Eigen::Vector3d(1.0, -2.0, 0.5));
  expect_near(camera.eye(), before + Eigen::Vector3d(1.0, -2.0, 0.5), 1e-12);
  EXPECT_EQ(camera.camera(1.0).target, Eigen::Vector3f(1.0f, -2.0f, 0.5f));
}

}  // namespace
}  // namespace tumble::app::viewer
