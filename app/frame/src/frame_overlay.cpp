// The overlay panel of a frame: the scene's title, the integrator and time, a legend of the
// items shown, the drift plots of the invariants (InvariantDrift, recorded at every observed
// frame) and the blow-up, when there is one.
//
// Size rule: the text is 13 px at 1280x720, proportional to the frame and to render.font_scale,
// never under 10 px; paddings and plot heights follow it. The panel is kept within 18 % of the
// frame's pixels (the bound is 20 %; the estimate below is within a few pixels of ImGui's
// layout): when it would be larger, the legend lines go first (last first), then the plots
// shrink to twice the text height, then the |L| plot and finally the energy plot are dropped.
// The title, integrator, time and blow-up lines always stay.
#include <cmath>
#include <cstdio>

#include "app/frame/overlay_fit.hpp"
#include "engine/dynamics/integrators.hpp"
#include "frame_builder_impl.hpp"
#include "render/overlay_layout.hpp"

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
  panel.font_px = render::overlay_font_px(settings.width, settings.height, settings.font_scale);
  const float unit = panel.font_px / render::kDefaultFontPx;
  panel.position_px = Eigen::Vector2f(10.0f * unit, 10.0f * unit);
  const engine::SimulationSettings& run = simulation.settings();
  panel.lines.push_back("integrator " + engine::integrator_info(run.integrator).name +
                        format(", dt = %g s", run.dt));
  panel.lines.push_back(
      format("t = %.3f s of %g s", simulation.time(), simulation.settings().duration));
  if (const auto& blow_up = simulation.blow_up()) {
    const std::string line =
        format("blew up at t = %.4g s", blow_up->time) + " (" + blow_up->reason + ")";
    panel.lines.push_back(line);
    list.labels.push_back(
        {line, std::nullopt,
         Eigen::Vector2f(panel.position_px.x(), static_cast<float>(settings.height) -
                                                    panel.font_px - panel.position_px.y()),
         kBlowUpColour, panel.font_px});
  }
  const std::size_t first_legend = panel.lines.size();
  if (show.angular_velocity) panel.lines.push_back("yellow arrow: angular velocity w");
  if (show.angular_momentum) panel.lines.push_back("violet arrow: angular momentum L");
  if (show.herpolhode) panel.lines.push_back("orange: herpolhode (w tip in the world)");
  if (show.polhode) panel.lines.push_back("blue: polhode (w tip in the body)");
  // Drift when the quantity is an invariant of the scene, change otherwise; relative drifts
  // span decades (1e-15 to 1e-1), hence the log axis.
  const auto until = static_cast<long>(end);
  const float plot_height = std::clamp(0.06f * static_cast<float>(settings.height),
                                       2.5f * panel.font_px, 5.0f * panel.font_px);
  render::Plot energy{conservative ? "energy drift" : "energy change",
                      {energy_drift.begin(), energy_drift.begin() + until},
                      std::nullopt,
                      std::nullopt,
                      plot_height,
                      render::PlotAxis::kLog};
  render::Plot momentum{torque_free ? "|L| drift" : "|L| change",
                        {momentum_drift.begin(), momentum_drift.begin() + until},
                        std::nullopt,
                        std::nullopt,
                        plot_height,
                        render::PlotAxis::kLog};
  panel.plots = {std::move(energy), std::move(momentum)};
  fit_overlay_panel(panel, first_legend, settings.width, settings.height);
  // Labels drawn so far (w, L) get the panel's text size.
  for (render::Label& label : list.labels) {
    if (label.font_px <= 0.0f) label.font_px = panel.font_px;
  }
  list.panels.push_back(std::move(panel));
}

}  // namespace tumble::app
