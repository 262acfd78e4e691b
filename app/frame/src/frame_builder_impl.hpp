#pragma once
// The state behind FrameBuilder (private to the app's frame builder): what is fixed at
// construction (how each body is drawn, the camera rig) and the history observe() records.
// Its members are defined by concern: frame_builder.cpp (construction, framing, build),
// frame_body_items.cpp (each body's mesh, arrows and axes), frame_paths.cpp (polhode,
// herpolhode, trails), frame_overlay.cpp (the overlay panel and its drift plots),
// frame_forces.cpp (springs and pivots).

#include <Eigen/Core>
#include <algorithm>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "app/frame/frame_builder.hpp"
#include "camera_framing.hpp"

namespace tumble::app {
namespace detail {

/// Body axes drawn this many bounding radii long (they stick out of the body).
inline constexpr double kAxisLength = 1.25;

/// Everything constant about how one body is drawn.
struct BodyLook {
  render::MeshId mesh;
  std::optional<render::MeshId> ellipsoid;
  render::Rgba colour;
  double radius = 1.0;       ///< bounding radius of the drawn geometry about the COM, m
  double omega_scale = 0.0;  ///< m of arrow per rad/s
  /// The w scale that puts the arrow's tip on the drawn inertia ellipsoid (used while it is
  /// shown; the plain scale when the body does not turn).
  double ellipsoid_omega_scale = 0.0;
  double momentum_scale = 0.0;                                ///< m of arrow per kg m^2/s
  Eigen::Vector3d ellipsoid_radii = Eigen::Vector3d::Zero();  ///< principal frame, m

  double omega_scale_for(const ShowSettings& show) const {
    return show.inertia_ellipsoid ? ellipsoid_omega_scale : omega_scale;
  }
};

/// How one body's supports are drawn: its springs' coil radius, and the far end of its pivot's
/// stem (the pivot is fixed in the world, so is the stem).
struct SupportLook {
  double coil_radius = 0.0;                            ///< m
  Eigen::Vector3d stem_end = Eigen::Vector3d::Zero();  ///< world, m
};

/// The points of a coil from `from` to `to` (world, m) of `radius`: straight leads at both
/// ends and a fixed number of turns between them, so that it stretches with the distance.
std::vector<Eigen::Vector3f> coil_points(const Eigen::Vector3d& from, const Eigen::Vector3d& to,
                                         double radius);

/// Shrinks the arrows of `list` about their tails by one common factor (at most 1) so that
/// every tip whose tail is in the image projects inside it, `margin` pixels from its edges; a
/// label anchored at a tip moves with it (frame_arrow_fit.cpp). Returns the factor.
double keep_arrows_inside(render::DrawList& list, int width, int height, float margin);

}  // namespace detail

struct FrameBuilder::Impl {
  RenderSettings settings;
  std::string title;
  std::vector<detail::BodyLook> looks;
  std::vector<detail::SupportLook> supports;  ///< per body
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
  /// Appends the invariants' drift at the simulation's time to the plots' history.
  void record_drift(const engine::Simulation& simulation);
  /// Appends w (world and body) and the trail points at the simulation's time to the paths.
  void record_paths(const engine::Simulation& simulation);

  /// Settles `supports` from the scene (after frame_the_run(), which sets the ground height).
  void settle_supports(const CompiledScene& scene);
  /// Body `index`'s springs (coils to their anchors) and pivot (stem, marker and link to the
  /// centre of mass).
  void add_supports(const engine::BodyModel& body, const engine::BodyState& state,
                    std::size_t index, const ShowSettings& show, render::DrawList& list) const;
  void add_body_items(const engine::BodyModel& body, const engine::BodyState& state,
                      std::size_t index, std::size_t end, const ShowSettings& show,
                      render::DrawList& list) const;
  /// Body `index`'s herpolhode and polhode over the first `end` observed frames, carried with
  /// its rotation centre `centre` and drawn at the w arrow's scale.
  void add_poinsot_paths(std::size_t index, const engine::BodyState& state,
                         const Eigen::Vector3d& centre, double omega_scale, std::size_t end,
                         const ShowSettings& show, render::DrawList& list) const;
  /// The last `seconds` of each trail up to time `now` (the first `end` observed frames).
  void add_trails(double now, std::size_t end, const ShowSettings& show,
                  render::DrawList& list) const;
  void add_overlay(const engine::Simulation& simulation, std::size_t end, const ShowSettings& show,
                   render::DrawList& list) const;
};

}  // namespace tumble::app
