// The overlay panel of a frame: the scene's title, the integrator and time, a legend of the
// items shown, the drift plots of the invariants (InvariantDrift, recorded at every observed
// frame) and the blow-up, when there is one.
#include <cmath>
#include <cstdio>

#include "engine/integrators.hpp"
#include "frame_builder_impl.hpp"

namespace tumble::app {
namespace {

constexpr render::Rgba kBlowUpColour{1.0f, 0.2f, 0.15f, 1.0f};

std::string format(const char* pattern, double a, double b = 0.0) {
  char buffer[160];
  std::snprintf(buffer, sizeof buffer, pattern, a, b);
  return buffer;
}

}  // namespace

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

void FrameBuilder::Impl::record_drift(const engine::Simulation& simulation) {
  const InvariantDrift::Values now = drift(simulation.bodies(), simulation.states());
  energy_drift.push_back(static_cast<float>(now.energy));
  momentum_drift.push_back(static_cast<float>(now.momentum));
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

}  // namespace tumble::app
