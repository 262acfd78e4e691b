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

#include "camera_framing.hpp"
#include "draw_meshes.hpp"
#include "engine/integrators.hpp"
#include "engine/primitive_meshes.hpp"
#include "engine/principal_frame.hpp"

namespace tumble::app {
namespace {

using render::Rgba;

constexpr std::array<Rgba, 6> kBodyPalette = {{{0.86f, 0.55f, 0.26f, 1.0f},
                                               {0.30f, 0.62f, 0.68f, 1.0f},
                                               {0.62f, 0.45f, 0.72f, 1.0f},
                                               {0.55f, 0.66f, 0.32f, 1.0f},
                                               {0.80f, 0.40f, 0.45f, 1.0f},
                                               {0.55f, 0.55f, 0.58f, 1.0f}}};
constexpr std::array<Rgba, 4> kTrailPalette = {{{0.10f, 0.42f, 0.85f, 1.0f},
                                                {0.85f, 0.20f, 0.55f, 1.0f},
                                                {0.10f, 0.60f, 0.35f, 1.0f},
                                                {0.45f, 0.30f, 0.10f, 1.0f}}};
constexpr Rgba kOmegaColour{0.98f, 0.78f, 0.10f, 1.0f};
constexpr Rgba kMomentumColour{0.62f, 0.18f, 0.80f, 1.0f};
constexpr Rgba kHerpolhodeColour{0.90f, 0.50f, 0.05f, 1.0f};
constexpr Rgba kPolhodeColour{0.15f, 0.30f, 0.95f, 1.0f};
constexpr Rgba kEllipsoidColour{0.55f, 0.75f, 0.95f, 0.30f};
constexpr std::array<Rgba, 3> kAxisColours = {
    {{0.90f, 0.15f, 0.15f, 1.0f}, {0.15f, 0.75f, 0.20f, 1.0f}, {0.15f, 0.30f, 0.95f, 1.0f}}};
constexpr std::array<Rgba, 3> kPrincipalAxisColours = {
    {{1.00f, 0.55f, 0.55f, 1.0f}, {0.55f, 0.95f, 0.55f, 1.0f}, {0.55f, 0.65f, 1.00f, 1.0f}}};
constexpr Rgba kBlowUpColour{1.0f, 0.2f, 0.15f, 1.0f};

/// Initial |w| drawn as this fraction of the body's size (bounding diameter); |L| likewise.
constexpr double kOmegaArrowFraction = 0.8;
constexpr double kMomentumArrowFraction = 1.0;
/// Longest semi-axis of the drawn inertia ellipsoid, in bounding radii of the body.
constexpr double kEllipsoidFraction = 1.15;
/// Body axes drawn this many bounding radii long (they stick out of the body).
constexpr double kAxisLength = 1.25;

/// Everything constant about how one body is drawn.
struct BodyLook {
  render::MeshId mesh;
  std::optional<render::MeshId> ellipsoid;
  Rgba colour;
  double radius = 1.0;          ///< bounding radius of the drawn geometry about the COM, m
  double omega_scale = 0.0;  ///< m of arrow per rad/s
  /// The w scale that puts the arrow's tip on the drawn inertia ellipsoid (used while it is
  /// shown; the plain scale when the body does not turn).
  double ellipsoid_omega_scale = 0.0;
  double momentum_scale = 0.0;  ///< m of arrow per kg m^2/s
  Eigen::Vector3d ellipsoid_radii = Eigen::Vector3d::Zero();  ///< principal frame, m

  double omega_scale_for(const ShowSettings& show) const {
    return show.inertia_ellipsoid ? ellipsoid_omega_scale : omega_scale;
  }
};

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

std::vector<Eigen::Vector3f> to_float(const std::vector<Eigen::Vector3d>& points,
                                      std::size_t first) {
  std::vector<Eigen::Vector3f> out;
  out.reserve(points.size() - std::min(first, points.size()));
  for (std::size_t i = first; i < points.size(); ++i) out.push_back(points[i].cast<float>());
  return out;
}

std::string format(const char* pattern, double a, double b = 0.0) {
  char buffer[160];
  std::snprintf(buffer, sizeof buffer, pattern, a, b);
  return buffer;
}

}  // namespace

struct FrameBuilder::Impl {
  RenderSettings settings;
  std::string title;
  std::vector<BodyLook> looks;
  detail::CameraRig rig;
  double ground_height = 0.0;
  InvariantDrift drift;
  bool conservative = true;  ///< every body: energy is an invariant
  bool torque_free = true;   ///< every body: |L| is an invariant

  // History, one entry per observed frame.
  std::vector<double> times;
  std::vector<float> energy_drift;
  std::vector<float> momentum_drift;
  std::vector<std::vector<Eigen::Vector3d>> herpolhode;  ///< per body: w (world)
  std::vector<std::vector<Eigen::Vector3d>> polhode;     ///< per body: w (principal frame)
  std::vector<std::vector<Eigen::Vector3d>> trails;      ///< per trail: world points

  void frame_the_run(const CompiledScene& scene,
                     const std::vector<const engine::TriangleMesh*>& geometry);
  /// Number of observed frames at or before `time`.
  std::size_t history_end(double time) const {
    return static_cast<std::size_t>(std::upper_bound(times.begin(), times.end(), time) -
                                    times.begin());
  }
  void add_body_items(const engine::BodyModel& body, const engine::BodyState& state,
                      std::size_t index, std::size_t end, const ShowSettings& show,
                      render::DrawList& list) const;
  void add_overlay(const engine::Simulation& simulation, std::size_t end, const ShowSettings& show,
                   render::DrawList& list) const;
};

InvariantDrift::InvariantDrift(const std::vector<engine::BodyModel>& bodies,
                               const std::vector<engine::BodyState>& initial) {
  const Values start = (*this)(bodies, initial);  // the sums, over the unit scales
  initial_energy_ = start.energy;
  initial_momentum_ = start.momentum;
  if (std::abs(initial_energy_) > 0.0) energy_scale_ = std::abs(initial_energy_);
  if (initial_momentum_ > 0.0) momentum_scale_ = initial_momentum_;
}

InvariantDrift::Values InvariantDrift::operator()(
    const std::vector<engine::BodyModel>& bodies,
    const std::vector<engine::BodyState>& states) const {
  const engine::Invariants sum = engine::total_invariants(bodies, states);
  return {(sum.energy - initial_energy_) / energy_scale_,
          (sum.momentum - initial_momentum_) / momentum_scale_};
}

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
    BodyLook look;
    look.mesh = renderer.upload(detail::shaded_mesh_data(geometry, 35.0));
    look.colour = kBodyPalette[i % kBodyPalette.size()];
    look.radius = std::max(detail::bounding_radius(geometry), 1e-6);
    const double size = 2.0 * look.radius;
    const Eigen::Vector3d omega = engine::angular_velocity(body, state);
    const double omega_norm = omega.norm();
    const double momentum_norm = state.angular_momentum.norm();
    look.omega_scale = kOmegaArrowFraction * size / (omega_norm > 0.0 ? omega_norm : 1.0);
    look.momentum_scale =
        kMomentumArrowFraction * size / (momentum_norm > 0.0 ? momentum_norm : 1.0);
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
    if (settings.show.inertia_ellipsoid) {
      // Slightly inside the w tip, so the polhode drawn on it is not buried in it.
      look.ellipsoid = renderer.upload(detail::ellipsoid_mesh_data(0.995 * look.ellipsoid_radii));
    }
    impl.looks.push_back(look);
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

  // The camera, and the ground a hair below the lowest body point.
  const detail::Sphere bound = detail::enclosing_sphere(spheres);
  rig = detail::make_camera_rig(settings.camera, bound, followed,
                                static_cast<double>(settings.width) / settings.height);
  if (!std::isfinite(ground_height)) ground_height = bound.center.z() - bound.radius;
  ground_height -= 1e-3 * bound.radius;
}

void FrameBuilder::observe(const engine::Simulation& simulation) {
  Impl& impl = *impl_;
  const double time = simulation.time();
  if (!impl.times.empty() && time <= impl.times.back()) return;  // already seen
  impl.times.push_back(time);

  // Drift of the invariants, relative to their start values.
  const InvariantDrift::Values drift = impl.drift(simulation.bodies(), simulation.states());
  impl.energy_drift.push_back(static_cast<float>(drift.energy));
  impl.momentum_drift.push_back(static_cast<float>(drift.momentum));

  // w, unscaled (build() scales it as the w arrow is): in the world (herpolhode), in the body
  // (polhode).
  for (std::size_t i = 0; i < simulation.bodies().size(); ++i) {
    const engine::BodyModel& body = simulation.bodies()[i];
    const engine::BodyState& state = simulation.states()[i];
    const Eigen::Vector3d omega = engine::angular_velocity(body, state);
    if (impl.settings.show.herpolhode) impl.herpolhode[i].push_back(omega);
    if (impl.settings.show.polhode) impl.polhode[i].push_back(state.orientation.inverse() * omega);
  }

  // Trails: world points fixed in the bodies.
  for (std::size_t k = 0; k < impl.settings.show.trails.size(); ++k) {
    const TrailSettings& trail = impl.settings.show.trails[k];
    const engine::BodyModel& body = simulation.bodies()[trail.body];
    const engine::BodyState& state = simulation.states()[trail.body];
    impl.trails[k].push_back(state.position + engine::body_orientation(body, state) * trail.point);
  }
}

void FrameBuilder::Impl::add_body_items(const engine::BodyModel& body,
                                        const engine::BodyState& state, std::size_t index,
                                        std::size_t end, const ShowSettings& show,
                                        render::DrawList& list) const {
  const BodyLook& look = looks[index];
  const Eigen::Quaterniond body_turn = engine::body_orientation(body, state);
  const Eigen::Vector3d centre = engine::rotation_centre(body, state);
  const auto thickness = static_cast<float>(0.045 * look.radius);

  // The body itself.
  if (show.bodies) {
    Eigen::Affine3d pose = Eigen::Translation3d(state.position) * body_turn;
    list.meshes.push_back({look.mesh, pose.matrix().cast<float>(), look.colour});
  }

  // w and L from the rotation centre, at their fixed scales.
  const double omega_scale = look.omega_scale_for(show);
  const Eigen::Vector3d omega = engine::angular_velocity(body, state);
  const Eigen::Vector3d omega_tip = centre + omega_scale * omega;
  const Eigen::Vector3d momentum_tip = centre + look.momentum_scale * state.angular_momentum;
  if (show.angular_velocity && omega.squaredNorm() > 0.0) {
    list.arrows.push_back({centre.cast<float>(), omega_tip.cast<float>(), kOmegaColour, thickness});
  }
  if (show.angular_momentum && state.angular_momentum.squaredNorm() > 0.0) {
    list.arrows.push_back(
        {centre.cast<float>(), momentum_tip.cast<float>(), kMomentumColour, 1.4f * thickness});
  }

  // Body axes (RGB = xyz) at the centre of mass; principal axes at the rotation centre, each as
  // long as its moment relative to the largest.
  if (show.body_axes) {
    const Eigen::Matrix3d axes = body_turn.toRotationMatrix();
    for (int a = 0; a < 3; ++a) {
      const Eigen::Vector3d tip = state.position + kAxisLength * look.radius * axes.col(a);
      list.arrows.push_back({state.position.cast<float>(), tip.cast<float>(),
                             kAxisColours[static_cast<std::size_t>(a)], 0.6f * thickness});
    }
  }
  if (show.principal_axes) {
    const Eigen::Matrix3d axes = state.orientation.toRotationMatrix();
    for (int a = 0; a < 3; ++a) {
      const double length = kAxisLength * look.radius * body.moments[a] / body.moments.maxCoeff();
      const Eigen::Vector3d tip = centre + length * axes.col(a);
      list.arrows.push_back({centre.cast<float>(), tip.cast<float>(),
                             kPrincipalAxisColours[static_cast<std::size_t>(a)], 0.6f * thickness});
    }
  }

  // Poinsot's ellipsoid, moving with the body about the rotation centre.
  if (show.inertia_ellipsoid && look.ellipsoid) {
    Eigen::Affine3d pose = Eigen::Translation3d(centre) * state.orientation;
    list.meshes.push_back({*look.ellipsoid, pose.matrix().cast<float>(), kEllipsoidColour});
  }

  // Herpolhode (the w tip's path in the world, carried with the centre) and polhode (its path
  // in the body, drawn where the body is now).
  if (show.herpolhode && end > 1 && herpolhode[index].size() >= end) {
    render::Polyline line{{}, kHerpolhodeColour, 2.5f};
    for (std::size_t k = 0; k < end; ++k) {
      line.points.push_back((centre + omega_scale * herpolhode[index][k]).cast<float>());
    }
    list.polylines.push_back(std::move(line));
  }
  if (show.polhode && end > 1 && polhode[index].size() >= end) {
    render::Polyline line{{}, kPolhodeColour, 2.5f};
    for (std::size_t k = 0; k < end; ++k) {
      line.points.push_back(
          (centre + omega_scale * (state.orientation * polhode[index][k])).cast<float>());
    }
    list.polylines.push_back(std::move(line));
  }

  // Names of the arrows, at their tips.
  if (show.overlay && show.angular_velocity && omega.squaredNorm() > 0.0) {
    list.labels.push_back({"w", omega_tip.cast<float>(), Eigen::Vector2f::Zero(), kOmegaColour});
  }
  if (show.overlay && show.angular_momentum && state.angular_momentum.squaredNorm() > 0.0) {
    list.labels.push_back(
        {"L", momentum_tip.cast<float>(), Eigen::Vector2f::Zero(), {0.85f, 0.55f, 1.0f, 1.0f}});
  }
}

void FrameBuilder::Impl::add_overlay(const engine::Simulation& simulation, std::size_t end,
                                     const ShowSettings& show, render::DrawList& list) const {
  render::OverlayPanel panel;
  panel.title = title;
  // Wide enough for the title (about 7 px per character of ImGui's default font).
  panel.width_px = std::clamp(7.2f * static_cast<float>(title.size()) + 24.0f, 320.0f,
                              std::max(320.0f, 0.45f * static_cast<float>(settings.width)));
  const engine::SimulationSettings& run = simulation.settings();
  panel.lines.push_back("integrator " + engine::integrator_info(run.integrator).name +
                        format(", dt = %g s", run.dt));
  panel.lines.push_back(
      format("t = %.3f s of %g s", simulation.time(), simulation.settings().duration));
  if (show.angular_velocity) panel.lines.push_back("yellow arrow: angular velocity w");
  if (show.angular_momentum) panel.lines.push_back("violet arrow: angular momentum L");
  if (show.herpolhode) panel.lines.push_back("orange: herpolhode (w tip in the world)");
  if (show.polhode) panel.lines.push_back("blue: polhode (w tip in the body)");
  const auto until = static_cast<long>(end);
  // Drift when the quantity is an invariant of the scene, change otherwise.
  panel.plots.push_back({conservative ? "energy drift" : "energy change",
                         {energy_drift.begin(), energy_drift.begin() + until},
                         std::nullopt,
                         std::nullopt,
                         50.0f});
  panel.plots.push_back({torque_free ? "|L| drift" : "|L| change",
                         {momentum_drift.begin(), momentum_drift.begin() + until},
                         std::nullopt,
                         std::nullopt,
                         50.0f});
  if (const auto& blow_up = simulation.blow_up()) {
    const std::string line =
        format("blew up at t = %.4g s", blow_up->time) + " (" + blow_up->reason + ")";
    panel.lines.push_back(line);
    list.labels.push_back({line, std::nullopt,
                           Eigen::Vector2f(12.0f, static_cast<float>(settings.height) - 32.0f),
                           kBlowUpColour});
  }
  list.panels.push_back(std::move(panel));
}

render::DrawList FrameBuilder::build(const engine::Simulation& simulation) const {
  return build(simulation, impl_->settings.show);
}

double FrameBuilder::reach() const { return impl_->rig.reach; }

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
  }

  // Trails: the last `seconds` of each.
  for (std::size_t k = 0; k < std::min(show.trails.size(), impl.trails.size()); ++k) {
    const double start = now - show.trails[k].seconds;
    const auto first = static_cast<std::size_t>(
        std::lower_bound(impl.times.begin(), impl.times.end(), start) - impl.times.begin());
    std::vector<Eigen::Vector3d> points(impl.trails[k].begin() + static_cast<long>(first),
                                        impl.trails[k].begin() + static_cast<long>(end));
    if (points.size() < 2) continue;
    list.polylines.push_back({to_float(points, 0), kTrailPalette[k % kTrailPalette.size()], 2.5f});
  }

  if (show.overlay) impl.add_overlay(simulation, end, show, list);
  return list;
}

}  // namespace tumble::app
