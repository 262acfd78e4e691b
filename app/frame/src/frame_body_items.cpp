// Each body's items in a frame: its mesh, the w and L arrows with their names, its body and
// principal axes, Poinsot's ellipsoid; then its polhode and herpolhode (frame_paths.cpp).
#include <Eigen/Geometry>
#include <array>

#include "frame_builder_impl.hpp"

namespace tumble::app {
namespace {

using detail::BodyLook;
using detail::kAxisLength;
using render::Rgba;

constexpr Rgba kOmegaColour{0.98f, 0.78f, 0.10f, 1.0f};
constexpr Rgba kMomentumColour{0.62f, 0.18f, 0.80f, 1.0f};
constexpr Rgba kMomentumLabelColour{0.85f, 0.55f, 1.0f, 1.0f};
constexpr Rgba kEllipsoidColour{0.55f, 0.75f, 0.95f, 0.30f};
constexpr std::array<Rgba, 3> kAxisColours = {
    {{0.90f, 0.15f, 0.15f, 1.0f}, {0.15f, 0.75f, 0.20f, 1.0f}, {0.15f, 0.30f, 0.95f, 1.0f}}};
constexpr std::array<Rgba, 3> kPrincipalAxisColours = {
    {{1.00f, 0.55f, 0.55f, 1.0f}, {0.55f, 0.95f, 0.55f, 1.0f}, {0.55f, 0.65f, 1.00f, 1.0f}}};

/// The thickness of a body's w arrow; L and the axes are drawn relative to it.
float arrow_thickness(const BodyLook& look) {
  return static_cast<float>(0.045 * look.radius);
}

/// w and L from the rotation centre, at their fixed scales, each named at its tip when the
/// overlay is on.
void add_spin_arrows(const BodyLook& look, const engine::BodyModel& body,
                     const engine::BodyState& state, const ShowSettings& show,
                     render::DrawList& list) {
  const Eigen::Vector3d centre = engine::rotation_centre(body, state);
  const float thickness = arrow_thickness(look);
  const Eigen::Vector3d omega = engine::angular_velocity(body, state);
  const Eigen::Vector3d omega_tip = centre + look.omega_scale_for(show) * omega;
  const Eigen::Vector3d momentum_tip = centre + look.momentum_scale * state.angular_momentum;
  if (show.angular_velocity && omega.squaredNorm() > 0.0) {
    list.arrows.push_back({centre.cast<float>(), omega_tip.cast<float>(), kOmegaColour, thickness});
    if (show.overlay) {
      list.labels.push_back({"w", omega_tip.cast<float>(), Eigen::Vector2f::Zero(), kOmegaColour});
    }
  }
  if (show.angular_momentum && state.angular_momentum.squaredNorm() > 0.0) {
    list.arrows.push_back(
        {centre.cast<float>(), momentum_tip.cast<float>(), kMomentumColour, 1.4f * thickness});
    if (show.overlay) {
      list.labels.push_back(
          {"L", momentum_tip.cast<float>(), Eigen::Vector2f::Zero(), kMomentumLabelColour});
    }
  }
}

/// Body axes (RGB = xyz) at the centre of mass; principal axes at the rotation centre, each as
/// long as its moment relative to the largest.
void add_axes(const BodyLook& look, const engine::BodyModel& body, const engine::BodyState& state,
              const ShowSettings& show, render::DrawList& list) {
  const float thickness = 0.6f * arrow_thickness(look);
  if (show.body_axes) {
    const Eigen::Matrix3d axes = engine::body_orientation(body, state).toRotationMatrix();
    for (int a = 0; a < 3; ++a) {
      const Eigen::Vector3d tip = state.position + kAxisLength * look.radius * axes.col(a);
      list.arrows.push_back({state.position.cast<float>(), tip.cast<float>(),
                             kAxisColours[static_cast<std::size_t>(a)], thickness});
    }
  }
  if (show.principal_axes) {
    const Eigen::Vector3d centre = engine::rotation_centre(body, state);
    const Eigen::Matrix3d axes = state.orientation.toRotationMatrix();
    for (int a = 0; a < 3; ++a) {
      const double length = kAxisLength * look.radius * body.moments[a] / body.moments.maxCoeff();
      const Eigen::Vector3d tip = centre + length * axes.col(a);
      list.arrows.push_back({centre.cast<float>(), tip.cast<float>(),
                             kPrincipalAxisColours[static_cast<std::size_t>(a)], thickness});
    }
  }
}

}  // namespace

void FrameBuilder::Impl::add_body_items(const engine::BodyModel& body,
                                        const engine::BodyState& state, std::size_t index,
                                        std::size_t end, const ShowSettings& show,
                                        render::DrawList& list) const {
  const BodyLook& look = looks[index];
  const Eigen::Vector3d centre = engine::rotation_centre(body, state);

  // The body itself.
  if (show.bodies) {
    Eigen::Affine3d pose =
        Eigen::Translation3d(state.position) * engine::body_orientation(body, state);
    list.meshes.push_back({look.mesh, pose.matrix().cast<float>(), look.colour});
  }
  add_spin_arrows(look, body, state, show, list);
  add_axes(look, body, state, show, list);

  // Poinsot's ellipsoid, moving with the body about the rotation centre.
  if (show.inertia_ellipsoid && look.ellipsoid) {
    Eigen::Affine3d pose = Eigen::Translation3d(centre) * state.orientation;
    list.meshes.push_back({*look.ellipsoid, pose.matrix().cast<float>(), kEllipsoidColour});
  }
  add_poinsot_paths(index, state, centre, look.omega_scale_for(show), end, show, list);
}

}  // namespace tumble::app
