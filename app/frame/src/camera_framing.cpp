#include "camera_framing.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <variant>

#include "engine/body/rigid_body.hpp"

namespace tumble::app::detail {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
/// Room left around the framed ball (1: it touches the image's shorter edges).
constexpr double kFramingMargin = 1.12;

/// Unit vector from the target to the eye at `azimuth_deg` about z (from +x), `elevation_deg`
/// above the xy plane.
Eigen::Vector3d view_direction(double azimuth_deg, double elevation_deg) {
  const double azimuth = azimuth_deg * kDegree;
  const double elevation = elevation_deg * kDegree;
  return {std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
          std::sin(elevation)};
}

/// The distance at which a ball of `radius` fits a perspective view: the ball's silhouette
/// subtends asin(r / d), which must be at most half the narrower field of view.
double fitting_distance(double radius, double vertical_fov_deg, double aspect) {
  const double half_vertical = 0.5 * vertical_fov_deg * kDegree;
  const double half_horizontal = std::atan(aspect * std::tan(half_vertical));
  const double half_angle = std::min(half_vertical, half_horizontal);
  return kFramingMargin * radius / std::sin(half_angle);
}

}  // namespace

Sphere enclosing_sphere(const std::vector<Sphere>& spheres) {
  if (spheres.empty()) return {Eigen::Vector3d::Zero(), 1.0};
  Eigen::Vector3d low = spheres.front().center;
  Eigen::Vector3d high = low;
  for (const Sphere& s : spheres) {
    low = low.cwiseMin(s.center - Eigen::Vector3d::Constant(s.radius));
    high = high.cwiseMax(s.center + Eigen::Vector3d::Constant(s.radius));
  }
  Sphere out{0.5 * (low + high), 0.0};
  for (const Sphere& s : spheres) {
    out.radius = std::max(out.radius, (s.center - out.center).norm() + s.radius);
  }
  return out;
}

/// The largest |w| a torque-free body reaches. With x_i = L_i^2 (principal frame), |w|^2 =
/// sum x_i / I_i^2 is linear in x on the segment cut from x >= 0 by the invariants sum x_i = G^2
/// and sum x_i / I_i = 2T, so its maximum sits where one x_i is zero: solve each pair.
double largest_free_omega(const engine::BodyModel& body, const engine::BodyState& state) {
  const double momentum_squared = state.angular_momentum.squaredNorm();
  const double twice_kinetic = engine::angular_velocity(body, state).dot(state.angular_momentum);
  const Eigen::Vector3d& moments = body.moments;
  double largest = 0.0;
  for (int i = 0; i < 3; ++i) {
    for (int j = i + 1; j < 3; ++j) {
      const double a = 1.0 / moments[i];
      const double b = 1.0 / moments[j];
      if (a == b) {
        largest = std::max(largest, momentum_squared * a * a);
        continue;
      }
      // x_i + x_j = G^2, a x_i + b x_j = 2T.
      const double x_i = (twice_kinetic - b * momentum_squared) / (a - b);
      const double x_j = momentum_squared - x_i;
      const double slack = 1e-9 * momentum_squared;
      if (x_i < -slack || x_j < -slack) continue;
      largest = std::max(largest, std::max(x_i, 0.0) * a * a + std::max(x_j, 0.0) * b * b);
    }
  }
  return std::sqrt(largest);
}

MotionBound motion_bound(const engine::BodyModel& body, const engine::BodyState& state,
                         const engine::TriangleMesh& geometry, double duration, double body_radius,
                         double reach, double arrows) {
  MotionBound out;
  const double offset = body.center_offset.norm();
  // Around its pivot, within a spring's energy reach, or along its straight or parabolic path.
  Eigen::Vector3d acceleration = Eigen::Vector3d::Zero();
  const engine::Spring* spring = nullptr;
  bool through_centre = true;  // every spring attached at the centre of mass
  for (const engine::ForceTerm& term : body.forces) {
    if (const auto* gravity = std::get_if<engine::Gravity>(&term)) {
      acceleration += gravity->acceleration;
    }
    if (const auto* s = std::get_if<engine::Spring>(&term)) {
      spring = s;
      through_centre = through_centre && s->attach.isZero();
    }
  }
  if (body.pivoted) {
    out.spheres.push_back({body.pivot, std::max(offset + reach, arrows)});
    out.body = {state.position, std::max(reach, offset + arrows)};
    // The ground under the body as it starts (a top stands on its pivot).
    const Eigen::Quaterniond turn = engine::body_orientation(body, state);
    for (const Eigen::Vector3d& p : geometry.positions) {
      out.lowest = std::min(out.lowest, (state.position + turn * p).z());
    }
    out.lowest = std::min(out.lowest, body.pivot.z());
  } else if (spring && spring->stiffness > 0.0) {
    // With x = p - R a (p the attachment point), the potential is (k/2) |p - q|^2 + m g . (R a)
    // up to a constant, q = anchor + m g / k the equilibrium of p; m g . (R a) >= -m |g| |a|,
    // so (k/2) |p - q|^2 never exceeds the energy at the start above that floor (damping only
    // lowers it). The camera holds that ball of p, the body around it and the anchor.
    const double k = spring->stiffness;
    const Eigen::Vector3d q = spring->anchor + body.mass * acceleration / k;
    const Eigen::Vector3d turned = state.orientation * spring->attach;
    const Eigen::Vector3d p = engine::rotation_centre(body, state) + turned;
    // A spring attached at the centre of mass exerts no torque about it, so the rotation never
    // trades energy with the stretch: the translational energy alone bounds it (a tumbling
    // body on such a spring stays as large as a still one).
    const double rotational =
        through_centre ? 0.0
                       : 0.5 * engine::angular_velocity(body, state).dot(state.angular_momentum);
    const double kinetic = 0.5 * body.mass * state.velocity.squaredNorm() + rotational;
    const double budget = kinetic + 0.5 * k * (p - q).squaredNorm() -
                          body.mass * acceleration.dot(turned) +
                          body.mass * acceleration.norm() * spring->attach.norm();
    const double radius =
        std::sqrt(std::max(0.0, 2.0 * budget / k)) + spring->attach.norm() + reach;
    out.spheres.push_back({q, radius});
    out.spheres.push_back({spring->anchor, 0.0});
    out.lowest = std::min(out.lowest, q.z() - radius);
    out.body = {state.position, reach};
  } else {
    constexpr int kSamples = 48;
    for (int k = 0; k <= kSamples; ++k) {
      const double t = duration * k / kSamples;
      const Eigen::Vector3d p = state.position + t * state.velocity + 0.5 * t * t * acceleration;
      out.spheres.push_back({p, reach});
      out.lowest = std::min(out.lowest, p.z() - body_radius);
    }
    out.body = {state.position, reach};
  }
  return out;
}

CameraRig make_camera_rig(const CameraSettings& settings, const Sphere& scene_bound,
                          const Sphere& follow_bound, double aspect) {
  CameraRig rig;
  rig.settings = settings;
  const bool follow = settings.mode == CameraSettings::Mode::kFollow;
  const Sphere& framed = follow ? follow_bound : scene_bound;

  // Target: the followed body, the explicit point or the centre of the framed ball.
  rig.target = follow ? framed.center : settings.target.value_or(framed.center);
  const double reach = (framed.center - rig.target).norm() + framed.radius;
  rig.reach = std::max(reach, 1e-6);

  // Eye: explicit, or at the distance that fits the ball, from azimuth and elevation.
  if (settings.eye) {
    rig.offset = *settings.eye - rig.target;
  } else {
    const double distance =
        settings.distance.value_or(fitting_distance(rig.reach, settings.fov_deg, aspect));
    rig.offset = distance * view_direction(settings.azimuth_deg, settings.elevation_deg);
  }
  return rig;
}

render::Camera camera_at(const CameraRig& rig, double time,
                         const Eigen::Vector3d& follow_position) {
  Eigen::Vector3d target = rig.target;
  Eigen::Vector3d offset = rig.offset;
  switch (rig.settings.mode) {
    case CameraSettings::Mode::kFixed:
      break;
    case CameraSettings::Mode::kOrbit: {
      // One turn about the world z axis per orbit period of simulated time.
      const double turn = 2.0 * std::numbers::pi * time / rig.settings.orbit_period;
      offset = Eigen::AngleAxisd(turn, Eigen::Vector3d::UnitZ()) * offset;
      break;
    }
    case CameraSettings::Mode::kFollow:
      target = follow_position;
      break;
  }

  render::Camera camera;
  camera.target = target.cast<float>();
  camera.eye = (target + offset).cast<float>();
  camera.up = Eigen::Vector3f::UnitZ();
  camera.vertical_fov_deg = static_cast<float>(rig.settings.fov_deg);
  // Depth range: the framed ball, plus the ground the renderer draws out to ~4 distances.
  const double distance = offset.norm();
  camera.near_plane =
      static_cast<float>(std::max(2e-3 * distance, 0.5 * (distance - 1.5 * rig.reach)));
  camera.far_plane = static_cast<float>(8.0 * (distance + rig.reach));
  return camera;
}

}  // namespace tumble::app::detail
