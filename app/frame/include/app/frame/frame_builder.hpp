#pragma once
/// @file Turns simulation state into the renderer's draw list: the bridge between engine and
/// render (the only code that sees both).

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/scene/render_settings.hpp"
#include "app/scene/scene.hpp"
#include "engine/simulation/simulation.hpp"
#include "render/draw_list.hpp"
#include "render/renderer.hpp"

namespace tumble::app {

/// Builds one DrawList per video frame. Meshes are uploaded once, at construction; a body
/// given only by its principal moments is drawn as the uniform box with the same moments and
/// mass. History (trails, polhode, herpolhode, drift plots) is recorded by observe(), which
/// must be called at every frame time from the start, rendered or not, so that a frame range
/// of a render is identical to the same frames of a full render.
class FrameBuilder {
 public:
  FrameBuilder(const SceneDescription& description, const CompiledScene& scene,
               const RenderSettings& settings, render::Renderer& renderer);

  /// Records the history items at the simulation's current time.
  void observe(const engine::Simulation& simulation);

  /// The draw list of the simulation's current state (after observe() at this time).
  render::DrawList build(const engine::Simulation& simulation) const;

  /// Same, showing only the items of `show` (the viewer's toggles). Items whose history or
  /// geometry the construction's settings did not ask for stay hidden: the herpolhode,
  /// polhode and ellipsoid need them on at construction, trails index its trail list.
  render::DrawList build(const engine::Simulation& simulation, const ShowSettings& show) const;

  /// Radius around the camera's target that holds the whole motion (m).
  double reach() const;

  /// Later draw lists are laid out for `width` x `height` frames at `font_scale` (the viewer's
  /// window was resized, or its --font-scale): the overlay's text, plots and placement and the
  /// arrows' fit follow. The camera's framing stays as constructed (the viewer draws with its
  /// own camera); the history is kept.
  void set_frame(int width, int height, double font_scale);

 private:
  struct Impl;
  std::shared_ptr<Impl> impl_;
};

/// Relative drift of a run's invariants: the total energy and the sum of the bodies' |L|, each
/// as (now - start) / |start| (over 1 when the start value is zero). The overlay's plots and the
/// viewer's live plots both show it.
class InvariantDrift {
 public:
  InvariantDrift() = default;
  InvariantDrift(const std::vector<engine::BodyModel>& bodies,
                 const std::vector<engine::BodyState>& initial);
  struct Values {
    double energy = 0.0;
    double momentum = 0.0;
  };
  Values operator()(const std::vector<engine::BodyModel>& bodies,
                    const std::vector<engine::BodyState>& states) const;

 private:
  double initial_energy_ = 0.0;
  double energy_scale_ = 1.0;
  double initial_momentum_ = 0.0;
  double momentum_scale_ = 1.0;
};

/// Edge lengths (m) of the uniform box of `mass` whose principal moments about its centre are
/// `moments` (kg m^2): from I1 = m (b^2 + c^2) / 12 etc., a^2 = 6 (I2 + I3 - I1) / m. A side
/// that the moments make zero (a flat body, I1 + I2 = I3) is kept at a thousandth of the
/// longest so that the box can be drawn.
Eigen::Vector3d equivalent_box_size(double mass, const Eigen::Vector3d& moments);

}  // namespace tumble::app
