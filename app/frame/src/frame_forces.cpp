// What holds the bodies, drawn: each spring as a coil from its anchor to its attachment point,
// stretching with the distance; each pivot as a stem (the support, fixed in the world), a
// marker at the pivot point and a link from the pivot to the body's centre of mass (a rigid,
// massless rod: it shows how a body whose pivot lies outside its drawn geometry, such as the
// box drawn for a body given only by its inertia, hangs from or stands on its pivot).
//
// Coil, stem and link are polylines and the marker a dot, all of a constant width in pixels,
// so they stay visible at any framing.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <variant>

#include "frame_builder_impl.hpp"

namespace tumble::app {
namespace {

using render::Rgba;

constexpr Rgba kSpringColour{0.90f, 0.25f, 0.15f, 1.0f};
constexpr Rgba kStemColour{0.12f, 0.12f, 0.14f, 1.0f};
constexpr Rgba kMarkerColour{0.97f, 0.97f, 0.97f, 1.0f};
/// The pivot marker's diameter as a share of the frame height, and its least diameter: a dot
/// that reads at every frame size (22 px at 720p, 65 px at 2160p, 9 px on a 270-line GIF).
constexpr float kMarkerHeightShare = 0.03f;
constexpr float kMarkerMinPx = 9.0f;
/// Turns of a drawn coil, whatever its length (it stretches: the pitch changes).
constexpr int kCoilTurns = 10;
constexpr int kSegmentsPerTurn = 20;
/// Straight leads at each end of a coil, as fractions of its length.
constexpr double kLeadFraction = 0.08;
/// Coil radius and stem length in bounding radii of the body.
constexpr double kCoilFraction = 0.18;
constexpr double kStemFraction = 0.9;

/// Two unit vectors perpendicular to the unit `axis` and to each other.
std::pair<Eigen::Vector3d, Eigen::Vector3d> perpendiculars(const Eigen::Vector3d& axis) {
  const Eigen::Vector3d helper =
      std::abs(axis.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d first = axis.cross(helper).normalized();
  return {first, axis.cross(first)};
}

}  // namespace

namespace detail {

std::vector<Eigen::Vector3f> coil_points(const Eigen::Vector3d& from, const Eigen::Vector3d& to,
                                         double radius) {
  const Eigen::Vector3d span = to - from;
  const double length = span.norm();
  if (!(length > 0.0)) return {from.cast<float>(), to.cast<float>()};
  const Eigen::Vector3d axis = span / length;
  const auto [e1, e2] = perpendiculars(axis);
  std::vector<Eigen::Vector3f> points{from.cast<float>()};
  const Eigen::Vector3d start = from + kLeadFraction * span;
  const Eigen::Vector3d coil = (1.0 - 2.0 * kLeadFraction) * span;
  constexpr int kSegments = kCoilTurns * kSegmentsPerTurn;
  for (int k = 0; k <= kSegments; ++k) {
    const double u = static_cast<double>(k) / kSegments;
    const double angle = 2.0 * std::numbers::pi * kCoilTurns * u;
    // The radius tapers to zero at both ends so the coil meets its leads.
    const double taper = std::min(1.0, std::min(u, 1.0 - u) * 2.0 * kCoilTurns);
    const Eigen::Vector3d p =
        start + u * coil + taper * radius * (std::sin(angle) * e1 + (1.0 - std::cos(angle)) * e2);
    points.push_back(p.cast<float>());
  }
  points.push_back(to.cast<float>());
  return points;
}

}  // namespace detail

void FrameBuilder::Impl::settle_supports(const CompiledScene& scene) {
  supports.resize(scene.bodies.size());
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const engine::BodyModel& body = scene.bodies[i];
    const engine::BodyState& state = scene.initial[i];
    detail::SupportLook& support = supports[i];
    support.coil_radius = kCoilFraction * looks[i].radius;
    if (!body.pivoted) continue;
    // The stem points away from the body: up from a hanging body, down (to the ground, when it
    // is shown and below) under a standing one; without gravity, away from the centre of mass.
    Eigen::Vector3d gravity = Eigen::Vector3d::Zero();
    for (const engine::ForceTerm& term : body.forces) {
      if (const auto* g = std::get_if<engine::Gravity>(&term)) gravity += g->acceleration;
    }
    const Eigen::Vector3d away = body.pivot - state.position;
    Eigen::Vector3d direction = away.norm() > 0.0 ? Eigen::Vector3d(away.normalized())
                                                  : Eigen::Vector3d(Eigen::Vector3d::UnitZ());
    if (gravity.norm() > 0.0) {
      const Eigen::Vector3d down = gravity.normalized();
      direction = away.dot(down) > 0.0 ? down : Eigen::Vector3d(-down);
    }
    double length = kStemFraction * looks[i].radius;
    if (settings.show.ground && direction.z() < 0.0 && body.pivot.z() > ground_height) {
      length = (body.pivot.z() - ground_height) / -direction.z();
    }
    support.stem_end = body.pivot + length * direction;
  }
}

void FrameBuilder::Impl::add_supports(const engine::BodyModel& body, const engine::BodyState& state,
                                      std::size_t index, const ShowSettings& show,
                                      render::DrawList& list) const {
  if (!show.bodies) return;
  const detail::SupportLook& support = supports[index];
  const Eigen::Vector3d centre = engine::rotation_centre(body, state);
  for (const engine::ForceTerm& term : body.forces) {
    const auto* spring = std::get_if<engine::Spring>(&term);
    if (!spring) continue;
    const Eigen::Vector3d attach = centre + state.orientation * spring->attach;
    list.polylines.push_back(
        {detail::coil_points(spring->anchor, attach, support.coil_radius), kSpringColour, 2.5f});
  }
  if (body.pivoted) {
    list.polylines.push_back(
        {{body.pivot.cast<float>(), support.stem_end.cast<float>()}, kStemColour, 4.0f});
    list.polylines.push_back(
        {{body.pivot.cast<float>(), state.position.cast<float>()}, kStemColour, 3.0f});
    const float marker_px =
        std::max(kMarkerMinPx, kMarkerHeightShare * static_cast<float>(settings.height));
    list.points.push_back({{body.pivot.cast<float>()}, kMarkerColour, marker_px});
  }
}

}  // namespace tumble::app
