// Fuzz target: scene files from text. The strict JSON parser (app/scene/strict_json.hpp), then
// the scene's validation (parse_scene), its `render` object (parse_render_settings) and, when
// every mesh it names is one of the small meshes in tests/fuzz/meshes, compiling it
// (compile_scene: import, mass properties, initial states). Meshes anywhere else are not read,
// so the fuzzer cannot wander into the machine's files (or /dev/zero).
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include "app/scene/render_settings.hpp"
#include "app/scene/scene.hpp"
#include "app/scene/strict_json.hpp"
#include "base/errors.hpp"
#include "fuzz_target.hpp"

namespace {

const std::filesystem::path kMeshDir = TUMBLE_FUZZ_MESH_DIR;

/// True when every mesh of `scene` is a file directly in kMeshDir.
bool meshes_are_ours(const tumble::app::SceneDescription& scene) {
  for (const auto& body : scene.bodies) {
    if (!body.mesh) continue;
    std::error_code error;
    const auto mesh = std::filesystem::weakly_canonical(*body.mesh, error);
    if (error || mesh.parent_path() != std::filesystem::weakly_canonical(kMeshDir) ||
        !std::filesystem::is_regular_file(mesh, error)) {
      return false;
    }
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text = tumble::fuzz::as_text(data, size);
  try {
    tumble::app::parse_strict_json(text, "fuzz.json");
  } catch (const tumble::InputError&) {
    return 0;  // a clean refusal
  }
  try {
    const auto scene = tumble::app::parse_scene(text, kMeshDir / "fuzz.json");
    std::vector<std::string> names;
    for (const auto& body : scene.bodies) names.push_back(body.name);
    if (scene.render) tumble::app::parse_render_settings(*scene.render, "fuzz.json", names);
    if (meshes_are_ours(scene)) tumble::app::compile_scene(scene, true);
  } catch (const tumble::InputError&) {
    // A clean refusal.
  }
  return 0;
}
