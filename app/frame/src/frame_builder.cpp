// Simulation state -> render::DrawList, one per video frame.
//
// Design note
// - Everything constant is settled at construction: meshes uploaded once (a body given only
//   by its inertia becomes the uniform box with the same mass and moments), one colour per
//   body, fixed arrow scales (the initial |w| and |L| map to set fractions of the body's size,
//   so a free body's L arrow keeps its length and a changing w shows as a changing arrow), and
//   the camera, framed on a bound of the whole run computed in closed form from the scene
//   (bodies' sizes, straight or parabolic paths of free bodies, pivots, spring reach).
// - History (trails, polhode, herpolhode, drift plots) is recorded only by observe(), at the
//   frame times, so a frame depends on the frames before it and not on which were rendered.
// - Poinsot's construction (Landau & Lifshitz, Mechanics, section 37): the tip of the scaled
//   w arrow lies on the inertia ellipsoid x^T J x = 2T s^2 (s: the w arrow's scale), which
//   therefore rolls on the invariable plane (normal L) traced by the herpolhode; the polhode is
//   the same tip seen in the body and lies on that ellipsoid.
#include "app/frame/frame_builder.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <variant>

#include "draw_meshes.hpp"
#include "engine/geometry/primitive_meshes.hpp"
#include "engine/mass/principal_frame.hpp"
#include "frame_builder_impl.hpp"

namespace tumble::app {
namespace {

using detail::BodyLook;
using detail::kAxisLength;
using render::Rgba;

constexpr std::array<Rgba, 6> kBodyPalette = {{{0.86f, 0.55f, 0.26f, 1.0f},
                                               {0.30f, 0.62f, 0.68f, 1.0f},
                                               {0.62f, 0.45f, 0.72f, 1.0f},
                                               {0.55f, 0.66f, 0.32f, 1.0f},
                                               {0.80f, 0.40f, 0.45f, 1.0f},
                                               {0.55f, 0.55f, 0.58f, 1.0f}}};
/// The longest w arrow of the run (the largest |w| of a free body, a quarter more than the
/// initial |w| otherwise) drawn this many bounding radii long; |L| likewise. The arrows stay
/// about as long as the body, so framing the body frames them too and the body stays large.
constexpr double kOmegaArrowReach = 1.1;
constexpr double kMomentumArrowReach = 1.2;
/// Longest semi-axis of the drawn inertia ellipsoid, in bounding radii of the body.
constexpr double kEllipsoidFraction = 1.15;

/// The drawn geometry of a body in its body frame: its mesh, or (made in `box`) the uniform
/// box with its mass and moments about the centre of mass, turned from its principal axes into
/// the body frame.
const engine::TriangleMesh& body_geometry(const engine::BodyModel& body,
                                          const std::optional<engine::TriangleMesh>& mesh,
                                          engine::TriangleMesh& box) {
  if (mesh) return *mesh;
  // Moments about the centre of mass (parallel axes back from the rotation centre).
  const Eigen::Vector3d c = body.center_offset;
  Eigen::Vector3d moments = body.moments;
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
  if (c.squaredNorm() > 0.0) {
    const Eigen::Matrix3d about_com =
        Eigen::Matrix3d(body.moments.asDiagonal()) -
        body.mass * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
    const engine::PrincipalFrame frame = engine::principal_frame(about_com);
    moments = frame.moments;
    axes = frame.axes;
  }
  box = engine::box_mesh(equivalent_box_size(body.mass, moments));
  engine::transform_mesh(box, body.principal_to_body.toRotationMatrix() * axes,
                         Eigen::Vector3d::Zero());
  return box;
}

/// How `body` is drawn in `colour`: its geometry uploaded, its arrow scales from its initial
/// state, and Poinsot's ellipsoid (uploaded `with_ellipsoid`).
BodyLook body_look(const engine::BodyModel& body, const engine::BodyState& state,
                   const engine::TriangleMesh& geometry, const Rgba& colour, bool with_ellipsoid,
                   render::Renderer& renderer) {
  BodyLook look;
  look.mesh = renderer.upload(detail::shaded_mesh_data(geometry, 35.0));
  look.colour = colour;
  look.radius = std::max(detail::bounding_radius(geometry), 1e-6);
  const Eigen::Vector3d omega = engine::angular_velocity(body, state);
  const double omega_norm = omega.norm();
  const double omega_max = body.torque_free()
                               ? std::max(omega_norm, detail::largest_free_omega(body, state))
                               : 1.25 * omega_norm;
  const double momentum_max = state.angular_momentum.norm() * (body.torque_free() ? 1.0 : 1.25);
  look.omega_scale = kOmegaArrowReach * look.radius / (omega_max > 0.0 ? omega_max : 1.0);
  look.momentum_scale =
      kMomentumArrowReach * look.radius / (momentum_max > 0.0 ? momentum_max : 1.0);
  // Poinsot's ellipsoid through the tip of the w arrow: semi-axes s sqrt(2T / I_i). While it
  // is shown, the w scale s makes its longest semi-axis a little longer than the body.
  const double twice_kinetic = omega.dot(state.angular_momentum);
  look.ellipsoid_omega_scale = look.omega_scale;
  if (twice_kinetic > 0.0) {
    look.ellipsoid_omega_scale =
        kEllipsoidFraction * look.radius * std::sqrt(body.moments.minCoeff() / twice_kinetic);
    look.ellipsoid_radii = look.ellipsoid_omega_scale * std::sqrt(twice_kinetic) *
                           body.moments.cwiseSqrt().cwiseInverse();
  } else {
    look.ellipsoid_radii = kEllipsoidFraction * look.radius *
                           (body.moments.minCoeff() * body.moments.cwiseInverse()).cwiseSqrt();
  }
  if (with_ellipsoid) {
    // Slightly inside the w tip, so the polhode drawn on it is not buried in it.
    look.ellipsoid = renderer.upload(detail::ellipsoid_mesh_data(0.995 * look.ellipsoid_radii));
  }
  return look;
}

}  // namespace

FrameBuilder::FrameBuilder(const SceneDescription& description, const CompiledScene& scene,
                           const RenderSettings& settings, render::Renderer& renderer)
    : impl_(std::make_shared<Impl>()) {
  Impl& impl = *impl_;
  impl.settings = settings;
  impl.title = description.name;

  // Meshes, colours and arrow scales, fixed for the whole run. The drawn geometry (a mesh of the
  // scene, or a box made here) also bounds the motion below.
  const std::optional<engine::TriangleMesh> none;
  std::vector<engine::TriangleMesh> boxes(scene.bodies.size());
  std::vector<const engine::TriangleMesh*> geometries;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const engine::BodyModel& body = scene.bodies[i];
    const engine::BodyState& state = scene.initial[i];
    const engine::TriangleMesh& geometry =
        body_geometry(body, i < scene.geometry.size() ? scene.geometry[i] : none, boxes[i]);
    geometries.push_back(&geometry);
    impl.looks.push_back(body_look(body, state, geometry, kBodyPalette[i % kBodyPalette.size()],
                                   settings.show.inertia_ellipsoid, renderer));
  }
  impl.herpolhode.resize(scene.bodies.size());
  impl.polhode.resize(scene.bodies.size());
  impl.trails.resize(settings.show.trails.size());

  // Invariants at the start, for the drift plots.
  impl.drift = InvariantDrift(scene.bodies, scene.initial);
  for (const engine::BodyModel& body : scene.bodies) {
    impl.conservative = impl.conservative && body.conservative();
    impl.torque_free = impl.torque_free && body.torque_free();
  }

  impl.frame_the_run(scene, geometries);
  impl.settle_supports(scene);
}

void FrameBuilder::Impl::frame_the_run(const CompiledScene& scene,
                                       const std::vector<const engine::TriangleMesh*>& geometry) {
  const ShowSettings& show = settings.show;
  const double duration = scene.settings.duration;
  std::vector<detail::Sphere> spheres;
  detail::Sphere followed;
  ground_height = std::numeric_limits<double>::infinity();

  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const engine::BodyModel& body = scene.bodies[i];
    const engine::BodyState& state = scene.initial[i];
    const BodyLook& look = looks[i];

    // How far the drawn items reach from the rotation centre (w: its exact bound for a free
    // body, a quarter more than at the start otherwise).
    double arrows = 0.0;
    const double omega_norm = engine::angular_velocity(body, state).norm();
    const double omega_max = body.torque_free()
                                 ? std::max(omega_norm, detail::largest_free_omega(body, state))
                                 : 1.25 * omega_norm;
    if (show.angular_velocity || show.herpolhode || show.polhode) {
      arrows = std::max(arrows, look.omega_scale_for(show) * omega_max);
    }
    if (show.angular_momentum) {
      arrows = std::max(arrows, look.momentum_scale * state.angular_momentum.norm() *
                                    (body.torque_free() ? 1.0 : 1.25));
    }
    if (show.inertia_ellipsoid) arrows = std::max(arrows, look.ellipsoid_radii.maxCoeff());
    if (show.principal_axes) arrows = std::max(arrows, kAxisLength * look.radius);
    double reach = std::max(look.radius, arrows);
    if (show.body_axes) reach = std::max(reach, kAxisLength * look.radius);

    // Where the body goes, in closed form.
    const detail::MotionBound motion =
        detail::motion_bound(body, state, *geometry[i], duration, look.radius, reach, arrows);
    spheres.insert(spheres.end(), motion.spheres.begin(), motion.spheres.end());
    ground_height = std::min(ground_height, motion.lowest);
    const detail::Sphere body_bound = motion.body;
    // Follow mode frames the followed body's ball around its centre of mass.
    if (i == settings.camera.follow_body) followed = body_bound;
  }

  // The camera, and the ground a hair below the lowest body point. A lone free body (no pivot,
  // no spring) under automatic framing is followed: its ball around the centre of mass is
  // framed and the target moves with it, so a thrown body stays large instead of the camera
  // backing off to hold its whole path.
  const detail::Sphere bound = detail::enclosing_sphere(spheres);
  CameraSettings camera = settings.camera;
  const bool automatic = camera.mode == CameraSettings::Mode::kFixed && !camera.eye &&
                         !camera.target && !camera.distance;
  if (automatic && scene.bodies.size() == 1 && !scene.bodies[0].pivoted &&
      std::none_of(scene.bodies[0].forces.begin(), scene.bodies[0].forces.end(),
                   [](const engine::ForceTerm& term) {
                     return std::holds_alternative<engine::Spring>(term);
                   })) {
    camera.mode = CameraSettings::Mode::kFollow;
    camera.follow_body = 0;
  }
  rig = detail::make_camera_rig(camera, bound, followed,
                                static_cast<double>(settings.width) / settings.height);
  if (!std::isfinite(ground_height)) ground_height = bound.center.z() - bound.radius;
  ground_height -= 1e-3 * bound.radius;
}

void FrameBuilder::observe(const engine::Simulation& simulation) {
  Impl& impl = *impl_;
  const double time = simulation.time();
  if (!impl.times.empty() && time <= impl.times.back()) return;  // already seen
  impl.times.push_back(time);

  impl.record_drift(simulation);
  impl.record_paths(simulation);
}

render::DrawList FrameBuilder::build(const engine::Simulation& simulation) const {
  return build(simulation, impl_->settings.show);
}

double FrameBuilder::reach() const {
  return impl_->rig.reach;
}

void FrameBuilder::set_frame(int width, int height, double font_scale) {
  impl_->settings.width = width;
  impl_->settings.height = height;
  impl_->settings.font_scale = font_scale;
}

render::DrawList FrameBuilder::build(const engine::Simulation& simulation,
                                     const ShowSettings& show) const {
  const Impl& impl = *impl_;
  render::DrawList list;

  // Camera and stage.
  const std::size_t followed =
      std::min(impl.settings.camera.follow_body, simulation.states().size() - 1);
  list.camera =
      detail::camera_at(impl.rig, simulation.time(), simulation.states()[followed].position);
  list.style.ground = show.ground;
  list.style.shadows = show.ground;
  list.style.ground_normal = Eigen::Vector3f::UnitZ();
  list.style.ground_height = static_cast<float>(impl.ground_height);

  // Bodies with their arrows and curves.
  const double now = simulation.time();
  const std::size_t end = impl.history_end(now);
  for (std::size_t i = 0; i < simulation.bodies().size(); ++i) {
    impl.add_body_items(simulation.bodies()[i], simulation.states()[i], i, end, show, list);
    impl.add_supports(simulation.bodies()[i], simulation.states()[i], i, show, list);
  }

  // Arrows that would leave the image (under an explicit camera) are shrunk together, and the
  // overlay says by how much.
  const double shrink =
      detail::keep_arrows_inside(list, impl.settings.width, impl.settings.height,
                                 0.02f * static_cast<float>(impl.settings.height));
  if (shrink < 1.0 && show.overlay) {
    char text[64];
    std::snprintf(text, sizeof text, "arrows drawn at %.2fx to stay in the frame", shrink);
    list.labels.push_back({text, std::nullopt,
                           Eigen::Vector2f(10.0f, static_cast<float>(impl.settings.height) - 24.0f),
                           Rgba{}});
  }
  impl.add_trails(now, end, show, list);
  if (show.overlay) impl.add_overlay(simulation, end, show, list);
  return list;
}

}  // namespace tumble::app
