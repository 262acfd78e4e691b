// Off-screen rendering throughput at 1280x720: rendering alone (bare body, and a full demo
// frame with ground + shadow, arrows, a trail and an overlay panel), and end to end into the
// PNG-sequence and MP4 sinks. Frames per second are reported as the `fps` counter (wall time).
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <numbers>

#include "media/image_sink.hpp"
#include "render/renderer.hpp"
#include "support/torus_mesh.hpp"

namespace {

using namespace tumble::render;
using namespace tumble::media;
using tumble::Image;

constexpr int kWidth = 1280;
constexpr int kHeight = 720;

MeshData torus(int rings, int sides, float major, float minor) {
  return tumble::testing::torus_mesh(rings, sides, major, minor);
}

/// range(0) = 0: ~2k triangles (32 x 32 torus), 1: ~20k triangles (100 x 100 torus),
/// 2: 1,000,000 triangles (1000 x 500 torus).
MeshData body_for(int64_t size) {
  if (size == 2) return torus(1000, 500, 0.6f, 0.25f);
  return size == 0 ? torus(32, 32, 0.6f, 0.25f) : torus(100, 100, 0.6f, 0.25f);
}

/// A demo-like frame: the body at step i, optionally with ground, arrows, trail and a panel.
DrawList frame_for(MeshId body, int step, bool full) {
  DrawList frame;
  frame.camera.eye = {2.5f, -3.5f, 1.8f};
  const float angle = 0.03f * static_cast<float>(step);
  const Eigen::Affine3f pose(Eigen::AngleAxisf(angle, Eigen::Vector3f(1, 2, 3).normalized()));
  frame.meshes.push_back({body, pose.matrix(), {0.85f, 0.55f, 0.25f, 1.0f}});
  if (!full) return frame;
  frame.style.ground = true;
  frame.style.ground_height = -1.0f;
  const Eigen::Matrix3f r = pose.linear();
  const tumble::render::Rgba axis_colours[3] = {
      {0.9f, 0.2f, 0.2f, 1}, {0.2f, 0.8f, 0.2f, 1}, {0.2f, 0.3f, 0.9f, 1}};
  for (int k = 0; k < 3; ++k) {
    frame.arrows.push_back({Eigen::Vector3f::Zero(), 1.2f * r.col(k), axis_colours[k], 0.03f});
  }
  Polyline trail;
  for (int i = 0; i < 500; ++i) {
    const float t = 0.01f * static_cast<float>(i);
    trail.points.emplace_back(1.2f * std::cos(t * 3 + angle), 1.2f * std::sin(t * 3 + angle),
                              0.3f * std::sin(5 * t));
  }
  frame.polylines.push_back(trail);
  OverlayPanel panel;
  panel.title = "t-handle";
  panel.lines = {"t = 1.234 s", "energy drift 1.2e-9"};
  Plot plot{"omega_x", {}, -1.0f, 1.0f, 50.0f};
  for (int i = 0; i < 200; ++i)
    plot.values.push_back(std::sin(0.05f * static_cast<float>(i + step)));
  panel.plots.push_back(plot);
  frame.panels.push_back(panel);
  frame.labels.push_back({"body", Eigen::Vector3f(0.0f, 0.0f, 0.9f), {}, {1, 1, 1, 1}});
  return frame;
}

// range(0): body size (0 ~2k, 1 ~20k triangles); range(1): MSAA samples; range(2): full frame.
void BM_Render(benchmark::State& state) {
  Renderer renderer({kWidth, kHeight, static_cast<int>(state.range(1))});
  const MeshId body = renderer.upload(body_for(state.range(0)));
  Image image;
  int step = 0;
  for (auto _ : state) {
    renderer.render(frame_for(body, step++, state.range(2) != 0), image);
    benchmark::DoNotOptimize(image.rgba.data());
  }
  state.counters["fps"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Render)
    ->ArgsProduct({{0, 1}, {1, 4}, {0, 1}})
    ->ArgNames({"body", "samples", "full"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);

/// End to end into a sink: render, queue, encode; finish() (flush and rename) is included.
void sink_benchmark(benchmark::State& state, const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / "tumble_bench_render";
  std::filesystem::create_directories(dir);
  Renderer renderer({kWidth, kHeight, static_cast<int>(state.range(1))});
  const MeshId body = renderer.upload(body_for(state.range(0)));
  Image image;
  int step = 0;
  SinkOptions options;
  options.width = kWidth;
  options.height = kHeight;
  options.fps = 30.0;
  auto sink = open_image_sink(dir / name, options);
  for (auto _ : state) {
    renderer.render(frame_for(body, step++, true), image);
    sink->write(image);
  }
  sink->finish();
  state.counters["fps"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  std::filesystem::remove_all(dir);
}

void BM_RenderToMp4(benchmark::State& state) {
  sink_benchmark(state, "out.mp4");
}
void BM_RenderToPng(benchmark::State& state) {
  sink_benchmark(state, "frames/");
}
BENCHMARK(BM_RenderToMp4)
    ->ArgsProduct({{0, 1}, {1, 4}})
    ->ArgNames({"body", "samples"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(150);
BENCHMARK(BM_RenderToPng)
    ->ArgsProduct({{0, 1}, {1, 4}})
    ->ArgNames({"body", "samples"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(150);

/// A 1,000,000-triangle body, level of detail on (range(0) = 1) or off: upload and the first
/// frame (the simplified copies that frame needs are made there), drawing alone (full = 0: the
/// bare body; 1: with ground, shadow, arrows, trail and panel), and end to end into H.264.
void BM_UploadMillion(benchmark::State& state) {
  const MeshData mesh = body_for(2);
  Renderer renderer({kWidth, kHeight, 1, state.range(0) != 0});
  Image image;
  for (auto _ : state) {
    const std::size_t keep = renderer.mesh_count();
    renderer.render(frame_for(renderer.upload(mesh), 0, false), image);
    benchmark::DoNotOptimize(image.rgba.data());
    renderer.release_meshes(keep);
  }
  state.counters["triangles"] = static_cast<double>(renderer.last_frame_triangles());
}
BENCHMARK(BM_UploadMillion)
    ->Arg(0)
    ->Arg(1)
    ->ArgName("lod")
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);

void BM_RenderMillion(benchmark::State& state) {
  Renderer renderer({kWidth, kHeight, 1, state.range(0) != 0});
  const MeshId body = renderer.upload(body_for(2));
  Image image;
  int step = 0;
  for (auto _ : state) {
    renderer.render(frame_for(body, step++, state.range(1) != 0), image);
    benchmark::DoNotOptimize(image.rgba.data());
  }
  state.counters["fps"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["triangles"] = static_cast<double>(renderer.last_frame_triangles());
}
BENCHMARK(BM_RenderMillion)
    ->ArgsProduct({{0, 1}, {0, 1}})
    ->ArgNames({"lod", "full"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);

void BM_RenderMillionToMp4(benchmark::State& state) {
  const auto dir = std::filesystem::temp_directory_path() / "tumble_bench_render_million";
  std::filesystem::create_directories(dir);
  Renderer renderer({kWidth, kHeight, 1, state.range(0) != 0});
  const MeshId body = renderer.upload(body_for(2));
  Image image;
  int step = 0;
  SinkOptions options;
  options.width = kWidth;
  options.height = kHeight;
  options.fps = 30.0;
  auto sink = open_image_sink(dir / "out.mp4", options);
  for (auto _ : state) {
    renderer.render(frame_for(body, step++, false), image);
    sink->write(image);
  }
  sink->finish();
  state.counters["fps"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  std::filesystem::remove_all(dir);
}
BENCHMARK(BM_RenderMillionToMp4)
    ->Arg(0)
    ->Arg(1)
    ->ArgName("lod")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(90);

}  // namespace

BENCHMARK_MAIN();
