// The viewer's frame at 1280x720 on the T-handle demo, without the window: the simulation
// stepped by one 60 Hz frame of wall time, the draw list, the 3D passes, the scene's overlay and
// the viewer's ImGui panels, read back. What SDL adds (texture upload and present) is measured
// by `tumble view --stats` under Xvfb (docs/performance.md, Viewer). The `fps` counter is frames
// per wall second.
//   BM_ViewerFrame          everything above (the figure the 60 frames/s is about)
//   BM_ViewerFrameNoPanels  the same without the ImGui panels
//   BM_ViewerStepOnly       only the simulation's share (1/60 s of the demo's rk4 steps)
#include <benchmark/benchmark.h>

#include <filesystem>

#include "app/viewer/viewer.hpp"
#include "app/viewer/viewer_panels.hpp"
#include "render/imgui_layer.hpp"
#include "render/renderer.hpp"

namespace {

using namespace tumble;

constexpr int kWidth = 1280;
constexpr int kHeight = 720;
constexpr double kFrameSeconds = 1.0 / 60.0;

std::filesystem::path demo() {
  return std::filesystem::path(TUMBLE_SOURCE_DIR) / "assets" / "scenes" / "t_handle_flip.json";
}

/// Keeps the demo playing: back to the start when it ends.
void keep_playing(app::viewer::Viewer& viewer) {
  if (viewer.session().finished()) {
    viewer.session().reset();
    viewer.session().set_paused(false);
  }
}

void BM_ViewerFrame(benchmark::State& state) {
  render::Renderer renderer({kWidth, kHeight, 1});
  render::ImGuiLayer layer(renderer);
  app::viewer::Viewer viewer(renderer, std::filesystem::temp_directory_path());
  if (!viewer.open(demo())) state.SkipWithError("demo scene did not open");
  app::viewer::Panels panels;
  tumble::Image image;
  for (auto _ : state) {
    keep_playing(viewer);
    viewer.update(kFrameSeconds);
    const render::DrawList list = viewer.frame();
    renderer.render(list, image, layer.pass(static_cast<float>(kFrameSeconds), [&] {
      panels.draw(viewer, {60.0, 16.7}, kWidth, kHeight);
    }));
    benchmark::DoNotOptimize(image.rgba.data());
  }
  state.counters["fps"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ViewerFrame)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3.0);

void BM_ViewerFrameNoPanels(benchmark::State& state) {
  render::Renderer renderer({kWidth, kHeight, 1});
  app::viewer::Viewer viewer(renderer, std::filesystem::temp_directory_path());
  if (!viewer.open(demo())) state.SkipWithError("demo scene did not open");
  tumble::Image image;
  for (auto _ : state) {
    keep_playing(viewer);
    viewer.update(kFrameSeconds);
    renderer.render(viewer.frame(), image);
    benchmark::DoNotOptimize(image.rgba.data());
  }
  state.counters["fps"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ViewerFrameNoPanels)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3.0);

void BM_ViewerStepOnly(benchmark::State& state) {
  render::Renderer renderer({64, 64, 1});
  app::viewer::Viewer viewer(renderer, std::filesystem::temp_directory_path());
  if (!viewer.open(demo())) state.SkipWithError("demo scene did not open");
  for (auto _ : state) {
    keep_playing(viewer);
    viewer.update(kFrameSeconds);
    benchmark::DoNotOptimize(viewer.session().time());
  }
}
BENCHMARK(BM_ViewerStepOnly)->Unit(benchmark::kMicrosecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
