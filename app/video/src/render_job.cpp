// A running render: the compiled scene, its simulation, the renderer and the frame builder.
#include <optional>
#include <stdexcept>

#include "app/frame/frame_builder.hpp"
#include "app/video/render_job.hpp"
#include "base/errors.hpp"
#include "engine/simulation/simulation.hpp"
#include "render/renderer.hpp"

namespace tumble::app {

render::RendererOptions renderer_options(const Antialiasing& antialiasing, int width, int height,
                                         bool lod) {
  render::RendererOptions options{width, height, antialiasing.samples, lod};
  if (antialiasing.mode == Antialiasing::Mode::kFxaa) {
    options.filter = render::AntialiasingFilter::fxaa;
  }
  return options;
}

using tumble::InputError;

struct RenderJob::Impl {
  // Declaration order is construction order: the builder holds the scene and the renderer.
  SceneDescription scene;
  RenderSettings settings;
  CompiledScene compiled;
  std::optional<engine::Simulation> simulation;
  std::unique_ptr<render::Renderer> own_renderer;  ///< empty when drawing with a shared one
  render::Renderer& renderer;
  FrameBuilder builder;
  std::size_t observed = 0;  ///< frame times observed so far

  Impl(const RenderPlan& plan, CompiledScene compiled_scene, render::Renderer* shared)
      : scene(plan.scene),
        settings(plan.settings),
        compiled(std::move(compiled_scene)),
        simulation(make_simulation(scene, compiled)),
        own_renderer(shared != nullptr ? nullptr
                                       : std::make_unique<render::Renderer>(
                                             renderer_options(settings.antialiasing, settings.width,
                                                              settings.height, settings.lod))),
        renderer(shared != nullptr ? *shared : *own_renderer),
        builder(scene, compiled, settings, renderer) {}

  static engine::Simulation make_simulation(const SceneDescription& scene,
                                            const CompiledScene& compiled) {
    try {
      return engine::Simulation(compiled.bodies, compiled.initial, compiled.settings);
    } catch (const InputError& error) {  // e.g. the exact integrator on a body with torques
      throw InputError(scene.file.string() + ": " + error.what());
    }
  }

  /// Steps while the next step ends at or before `time` (within rounding of dt).
  void step_to(double time) {
    engine::Simulation& sim = *simulation;
    const double dt = sim.settings().dt;
    while (!sim.finished()) {
      const std::size_t next = sim.steps() + 1;
      const double next_time =
          next == sim.total_steps() ? sim.settings().duration : static_cast<double>(next) * dt;
      if (next_time > time + 1e-9 * dt) break;
      sim.step();  // false on a blow-up, after which finished() holds
    }
  }
};

RenderJob::RenderJob(const RenderPlan& plan)
    : impl_(std::make_unique<Impl>(plan, compile_scene(plan.scene, /*keep_geometry=*/true),
                                   nullptr)) {}

RenderJob::RenderJob(const RenderPlan& plan, render::Renderer& renderer)
    : impl_(std::make_unique<Impl>(plan, compile_scene(plan.scene, /*keep_geometry=*/true),
                                   &renderer)) {}

RenderJob::RenderJob(const RenderPlan& plan, const CompiledScene& compiled,
                     render::Renderer& renderer)
    : impl_(std::make_unique<Impl>(
          plan,
          [&] {
            CompiledScene copy = compiled;
            copy.settings = simulation_settings(plan.scene);
            return copy;
          }(),
          &renderer)) {}

RenderJob::~RenderJob() = default;

void RenderJob::advance_to(std::size_t frame) {
  if (frame + 1 < impl_->observed) {
    throw std::logic_error("RenderJob::advance_to: frames must not go back");
  }
  while (impl_->observed <= frame) {
    impl_->step_to(frame_time(impl_->observed, impl_->settings.fps, impl_->settings.time_scale));
    impl_->builder.observe(*impl_->simulation);
    ++impl_->observed;
  }
}

void RenderJob::draw(Image& image) {
  impl_->renderer.render(build(), image);
}

render::DrawList RenderJob::build() const {
  return impl_->builder.build(*impl_->simulation);
}

const engine::Simulation& RenderJob::simulation() const {
  return *impl_->simulation;
}

}  // namespace tumble::app
