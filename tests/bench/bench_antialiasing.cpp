// Cost of anti-aliasing at 1280x720 on llvmpipe: a demo-like frame (a ~20k-triangle body,
// ground with its shadow, three arrows and an overlay panel) rendered and read back aliased,
// with the FXAA post-process (`tumble render`'s default) and with 4x multisampling. Frames per
// second are the `fps` counter (wall time); compare the modes of one run (the machine is shared).
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <numbers>
#include <vector>

#include "fxaa_blocks.hpp"
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

/// The T-handle demo's body (80 x 59 x 10 mm: a bar and a stem) framed like the demo (a third of
/// the frame height or more), tumbled by `angle`, with two arrows; no ground.
DrawList t_handle_frame(MeshId bar, MeshId stem, float angle, float line_scale) {
  DrawList frame;
  frame.camera.eye = {0.12f, -0.16f, 0.08f};
  frame.camera.target = {0.0f, 0.0f, 0.0f};
  frame.camera.near_plane = 0.01f;
  const Eigen::Affine3f pose(
      Eigen::AngleAxisf(angle, Eigen::Vector3f(0.3f, 1.0f, 0.2f).normalized()));
  const Eigen::Affine3f bar_pose = pose * Eigen::Translation3f(0.0f, 0.0195f, 0.0f);
  const Eigen::Affine3f stem_pose = pose * Eigen::Translation3f(0.0f, -0.0195f, 0.0f);
  frame.meshes.push_back({bar, bar_pose.matrix(), {0.80f, 0.55f, 0.25f, 1.0f}});
  frame.meshes.push_back({stem, stem_pose.matrix(), {0.80f, 0.55f, 0.25f, 1.0f}});
  frame.arrows.push_back({Eigen::Vector3f::Zero(),
                          pose.linear() * Eigen::Vector3f(0, 0.07f, 0),
                          {0.9f, 0.2f, 0.2f, 1.0f},
                          0.002f});
  frame.arrows.push_back({Eigen::Vector3f::Zero(),
                          Eigen::Vector3f(0.02f, 0.05f, 0.03f),
                          {0.2f, 0.3f, 0.9f, 1.0f},
                          0.002f});
  // A trail like the demo's, at the same width in the final image whatever the render's size.
  Polyline trail;
  for (int k = 0; k <= 60; ++k) {
    const float t = 0.07f * static_cast<float>(k);
    trail.points.emplace_back(0.055f * std::cos(t), 0.03f * std::sin(t),
                              0.02f * std::sin(1.7f * t));
  }
  trail.colour = {0.95f, 0.75f, 0.2f, 1.0f};
  trail.width_px = 2.0f * line_scale;
  frame.polylines.push_back(trail);
  return frame;
}

/// A box mesh with the given half extents (8 vertices, 12 triangles).
MeshData box(const Eigen::Vector3f& half) {
  MeshData mesh;
  for (int i = 0; i < 8; ++i) {
    mesh.positions.emplace_back((i & 1 ? 1.0f : -1.0f) * half.x(),
                                (i & 2 ? 1.0f : -1.0f) * half.y(),
                                (i & 4 ? 1.0f : -1.0f) * half.z());
  }
  mesh.indices = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                  2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
  return mesh;
}

/// Renders the T-handle frame at `angle` with `options`.
Image render_t_handle(const RendererOptions& options, float angle) {
  Renderer renderer(options);
  const MeshId bar = renderer.upload(box({0.04f, 0.01f, 0.005f}));
  const MeshId stem = renderer.upload(box({0.005f, 0.0195f, 0.005f}));
  return renderer.render(
      t_handle_frame(bar, stem, angle, static_cast<float>(options.width) / kWidth));
}

/// Mean absolute difference (0..255 a channel) of `image` to `big` (kScale times the size per
/// axis) averaged over kScale x kScale blocks, over the pixels whose block is not uniform.
double edge_error(const Image& image, const Image& big, int scale) {
  double sum = 0.0;
  long count = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      for (int c = 0; c < 3; ++c) {
        int lo = 255;
        int hi = 0;
        double mean = 0.0;
        for (int j = 0; j < scale; ++j) {
          for (int i = 0; i < scale; ++i) {
            const int v = big.pixel(x * scale + i, y * scale + j)[c];
            lo = std::min(lo, v);
            hi = std::max(hi, v);
            mean += v;
          }
        }
        if (hi - lo <= 8) continue;
        sum += std::abs(static_cast<double>(image.pixel(x, y)[c]) - mean / (scale * scale));
        ++count;
      }
    }
  }
  return count > 0 ? sum / static_cast<double>(count) : 0.0;
}

/// Edge error against a 16x supersampled reference (the aliased frame at 4x the size per axis,
/// 4x4 blocks averaged), T-handle at 1280x720 over three poses; range(0): 0 aliased, 1 the
/// filter, 2 2x MSAA, 3 4x MSAA. Counter `edge_error` (0..255); time per frame is measured by
/// BM_AntialiasingInterleaved.
void BM_AntialiasingEdgeError(benchmark::State& state) {
  RendererOptions options{kWidth, kHeight};
  if (state.range(0) == 1) options.filter = AntialiasingFilter::fxaa;
  if (state.range(0) >= 2) options.samples = state.range(0) == 2 ? 2 : 4;
  double error = 0.0;
  for (auto _ : state) {
    error = 0.0;
    for (const float angle : {0.3f, 1.1f, 2.0f}) {
      const Image big = render_t_handle({4 * kWidth, 4 * kHeight}, angle);
      error += edge_error(render_t_handle(options, angle), big, 4) / 3.0;
    }
  }
  state.counters["edge_error"] = error;
}
BENCHMARK(BM_AntialiasingEdgeError)
    ->DenseRange(0, 3)
    ->ArgName("mode")
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

/// The filter's block scan (fxaa_blocks.hpp) over a whole aliased 1280x720 frame: the
/// T-handle frame above with a path looping round it 480 times, like the default demo's
/// herpolhode late in the video (lines make most of the edges a scan must look at closely). The
/// renderer scans only the box where the scene drew; here the whole frame. Counter
/// `mpixels_per_s`: pixels scanned a second, in millions.
void BM_FindEdgeBlocks(benchmark::State& state) {
  Renderer renderer({kWidth, kHeight});
  const MeshId bar = renderer.upload(box({0.04f, 0.01f, 0.005f}));
  const MeshId stem = renderer.upload(box({0.005f, 0.0195f, 0.005f}));
  DrawList scene = t_handle_frame(bar, stem, 1.1f, 1.0f);
  Polyline path;
  for (int k = 0; k < 480; ++k) {
    const float t = 0.3f * static_cast<float>(k);
    const float r = 0.045f + 0.012f * std::sin(0.013f * static_cast<float>(k));
    path.points.emplace_back(r * std::cos(t), 0.015f * std::sin(1.3f * t), r * std::sin(t));
  }
  path.colour = {0.90f, 0.50f, 0.05f, 1.0f};
  path.width_px = 2.5f;
  scene.polylines.push_back(path);
  const Image frame = renderer.render(scene);
  std::vector<tumble::render::detail::BlockRun> runs;
  for (auto _ : state) {
    tumble::render::detail::find_edge_blocks(frame.rgba.data(), frame.width, frame.height, runs);
    benchmark::DoNotOptimize(runs.data());
  }
  state.counters["mpixels_per_s"] =
      benchmark::Counter(1e-6 * static_cast<double>(state.iterations()) * kWidth * kHeight,
                         benchmark::Counter::kIsRate);
  state.counters["runs"] = static_cast<double>(runs.size());
}
BENCHMARK(BM_FindEdgeBlocks)->Unit(benchmark::kMicrosecond)->MinTime(1.0);

}  // namespace

BENCHMARK_MAIN();
