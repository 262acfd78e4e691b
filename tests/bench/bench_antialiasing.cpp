// Cost of anti-aliasing at 1280x720 on llvmpipe: a demo-like frame (a ~20k-triangle body,
// ground with its shadow, three arrows and an overlay panel) rendered and read back aliased,
// with the FXAA post-process (`tumble render`'s default) and with 4x multisampling. Frames per
// second are the `fps` counter (wall time); compare the modes of one run (the machine is shared).
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>
#include <array>
#include <chrono>
#include <cmath>
#include <numbers>

#include "render/renderer.hpp"
#include "support/torus_mesh.hpp"

namespace {

using namespace tumble::render;
using tumble::Image;

constexpr int kWidth = 1280;
constexpr int kHeight = 720;

/// A torus with smooth normals, rings x sides x 2 triangles (100 x 100: 20k, like the demo's
/// meshes).
MeshData ring(int rings = 100, int sides = 100) {
  return tumble::testing::torus_mesh(rings, sides);
}

/// The body at step i over the ground (with shadow; none when `light`), with its body axes and
/// a small panel.
DrawList demo_frame(MeshId body, int step, bool light = false) {
  DrawList frame;
  frame.camera.eye = {2.5f, -3.5f, 1.8f};
  const float angle = 0.03f * static_cast<float>(step);
  const Eigen::Affine3f pose(Eigen::AngleAxisf(angle, Eigen::Vector3f(1, 2, 3).normalized()));
  frame.meshes.push_back({body, pose.matrix(), {0.85f, 0.55f, 0.25f, 1.0f}});
  frame.style.ground = !light;
  frame.style.ground_height = -1.0f;
  const Eigen::Matrix3f r = pose.linear();
  const Rgba colours[3] = {{0.9f, 0.2f, 0.2f, 1}, {0.2f, 0.8f, 0.2f, 1}, {0.2f, 0.3f, 0.9f, 1}};
  for (int k = 0; k < 3; ++k) {
    frame.arrows.push_back({Eigen::Vector3f::Zero(), 1.2f * r.col(k), colours[k], 0.03f});
  }
  OverlayPanel panel;
  panel.title = "ring";
  panel.lines = {"t = 1.234 s", "energy drift 1.2e-9"};
  frame.panels.push_back(panel);
  return frame;
}

/// range(0): 0 aliased, 1 FXAA, 2 4x MSAA.
void BM_Antialiasing(benchmark::State& state) {
  RendererOptions options{kWidth, kHeight};
  if (state.range(0) == 1) options.filter = AntialiasingFilter::fxaa;
  if (state.range(0) == 2) options.samples = 4;
  Renderer renderer(options);
  const MeshId body = renderer.upload(ring());
  Image image;
  int step = 0;
  renderer.render(demo_frame(body, step), image);  // the font atlas is built outside the timing
  for (auto _ : state) {
    renderer.render(demo_frame(body, step++), image);
    benchmark::DoNotOptimize(image.rgba.data());
  }
  state.counters["fps"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Antialiasing)
    ->DenseRange(0, 2)
    ->ArgName("mode")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);

/// range(0): 0 the frame above, 1 a light one like the T-handle demo's: a 2k-triangle ring
/// (32 x 32), no ground.
/// The three modes in turn, frame by frame, so that the load of a shared machine falls on all of
/// them alike: counters give each mode's milliseconds a frame and the ratios to aliased.
void BM_AntialiasingInterleaved(benchmark::State& state) {
  RendererOptions fxaa{kWidth, kHeight};
  fxaa.filter = AntialiasingFilter::fxaa;
  std::array<Renderer, 3> renderers{Renderer({kWidth, kHeight}), Renderer(fxaa),
                                    Renderer({kWidth, kHeight, 4})};
  std::array<MeshId, 3> bodies;
  Image image;
  for (std::size_t k = 0; k < 3; ++k) {
    bodies[k] = renderers[k].upload(state.range(0) == 0 ? ring() : ring(32, 32));
    renderers[k].render(demo_frame(bodies[k], 0, state.range(0) != 0), image);
  }
  std::array<double, 3> seconds{};
  int step = 0;
  for (auto _ : state) {
    for (std::size_t k = 0; k < 3; ++k) {
      const auto start = std::chrono::steady_clock::now();
      renderers[k].render(demo_frame(bodies[k], step, state.range(0) != 0), image);
      benchmark::DoNotOptimize(image.rgba.data());
      seconds[k] += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    ++step;
  }
  const double frames = static_cast<double>(state.iterations());
  state.counters["off_ms"] = 1e3 * seconds[0] / frames;
  state.counters["fxaa_ms"] = 1e3 * seconds[1] / frames;
  state.counters["msaa4_ms"] = 1e3 * seconds[2] / frames;
  state.counters["fxaa_ratio"] = seconds[1] / seconds[0];
  state.counters["msaa4_ratio"] = seconds[2] / seconds[0];
}
BENCHMARK(BM_AntialiasingInterleaved)
    ->DenseRange(0, 1)
    ->ArgName("light")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(3.0);

}  // namespace

BENCHMARK_MAIN();
