// The paths a frame shows, recorded at every observed frame: the tip of w in the world
// (herpolhode) and in the body (polhode), and trails of points fixed in the bodies.
#include <Eigen/Geometry>
#include <array>

#include "frame_builder_impl.hpp"

namespace tumble::app {
namespace {

using render::Rgba;

constexpr std::array<Rgba, 4> kTrailPalette = {{{0.10f, 0.42f, 0.85f, 1.0f},
                                                {0.85f, 0.20f, 0.55f, 1.0f},
                                                {0.10f, 0.60f, 0.35f, 1.0f},
                                                {0.45f, 0.30f, 0.10f, 1.0f}}};
constexpr Rgba kHerpolhodeColour{0.90f, 0.50f, 0.05f, 1.0f};
constexpr Rgba kPolhodeColour{0.15f, 0.30f, 0.95f, 1.0f};

std::vector<Eigen::Vector3f> to_float(const std::vector<Eigen::Vector3d>& points,
                                      std::size_t first) {
  std::vector<Eigen::Vector3f> out;
  out.reserve(points.size() - std::min(first, points.size()));
  for (std::size_t i = first; i < points.size(); ++i) out.push_back(points[i].cast<float>());
  return out;
}

}  // namespace

void FrameBuilder::Impl::record_paths(const engine::Simulation& simulation) {
  // w, unscaled (build() scales it as the w arrow is): in the world (herpolhode), in the body
  // (polhode).
  for (std::size_t i = 0; i < simulation.bodies().size(); ++i) {
    const engine::BodyModel& body = simulation.bodies()[i];
    const engine::BodyState& state = simulation.states()[i];
    const Eigen::Vector3d omega = engine::angular_velocity(body, state);
    if (settings.show.herpolhode) herpolhode[i].push_back(omega);
    if (settings.show.polhode) polhode[i].push_back(state.orientation.inverse() * omega);
  }

  // Trails: world points fixed in the bodies.
  for (std::size_t k = 0; k < settings.show.trails.size(); ++k) {
    const TrailSettings& trail = settings.show.trails[k];
    const engine::BodyModel& body = simulation.bodies()[trail.body];
    const engine::BodyState& state = simulation.states()[trail.body];
    trails[k].push_back(state.position + engine::body_orientation(body, state) * trail.point);
  }
}

void FrameBuilder::Impl::add_poinsot_paths(std::size_t index, const engine::BodyState& state,
                                           const Eigen::Vector3d& centre, double omega_scale,
                                           std::size_t end, const ShowSettings& show,
                                           render::DrawList& list) const {
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
}

void FrameBuilder::Impl::add_trails(double now, std::size_t end, const ShowSettings& show,
                                    render::DrawList& list) const {
  for (std::size_t k = 0; k < std::min(show.trails.size(), trails.size()); ++k) {
    const double start = now - show.trails[k].seconds;
    const auto first = static_cast<std::size_t>(
        std::lower_bound(times.begin(), times.end(), start) - times.begin());
    std::vector<Eigen::Vector3d> points(trails[k].begin() + static_cast<long>(first),
                                        trails[k].begin() + static_cast<long>(end));
    if (points.size() < 2) continue;
    list.polylines.push_back({to_float(points, 0), kTrailPalette[k % kTrailPalette.size()], 2.5f});
  }
}

}  // namespace tumble::app
