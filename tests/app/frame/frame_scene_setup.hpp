#pragma once
// The frame tests' shared set-up: a scene from JSON text, compiled with its geometry, its render
// settings at a given frame size, and one headless renderer per frame size (a GL context per
// test would be slow).

#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/frame/frame_builder.hpp"

namespace tumble::testing {

/// The renderer of every frame test drawing at `width` x `height`.
inline render::Renderer& frame_test_renderer(int width, int height) {
  static std::map<std::pair<int, int>, std::unique_ptr<render::Renderer>> renderers;
  std::unique_ptr<render::Renderer>& renderer = renderers[{width, height}];
  if (!renderer)
    renderer = std::make_unique<render::Renderer>(render::RendererOptions{width, height, 1});
  return *renderer;
}

/// A scene, compiled with its geometry, and the render settings read from its `render` object,
/// drawn at `width` x `height`.
struct FrameSceneSetup {
  app::SceneDescription description;
  app::CompiledScene scene;
  app::RenderSettings settings;

  FrameSceneSetup(const std::string& text, int width, int height) {
    description =
        app::parse_scene(text, std::string(TUMBLE_SOURCE_DIR) + "/assets/scenes/test.json");
    scene = app::compile_scene(description, true);
    std::vector<std::string> names;
    for (const auto& body : description.bodies) names.push_back(body.name);
    settings = app::parse_render_settings(description.render.value_or(nlohmann::json::object()),
                                          "test.json", names);
    settings.width = width;
    settings.height = height;
  }

  engine::Simulation simulation() const {
    return engine::Simulation(scene.bodies, scene.initial, scene.settings);
  }
  render::Renderer& renderer() const {
    return frame_test_renderer(settings.width, settings.height);
  }
  app::FrameBuilder builder() const {
    return app::FrameBuilder(description, scene, settings, renderer());
  }
};

}  // namespace tumble::testing
