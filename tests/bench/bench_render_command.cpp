// `tumble render` throughput on the default demo (t_handle_flip) at 1280x720, 60 frames a run:
//  - BM_RenderFrames: simulate, observe, build and draw, no output;
//  - BM_RenderToMp4 / BM_RenderToPng: the same into the H.264 and PNG-sequence sinks,
//    finish() (flush, encoder exit, rename) included;
//  - BM_RenderCommandMp4: the whole command, scene loading, mesh import, GL context, ffmpeg
//    start-up and the summary included.
// Frames per second are items_per_second (wall time). In the first three, the scene, renderer
// and sink are set up outside the timing and frame 0 is drawn once beforehand, so the ImGui font
// atlas (~60 ms, first overlay only) is not charged to the 60 frames.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <sstream>
#include <string>

#include "app/commands/render_command.hpp"
#include "media/image_sink.hpp"

namespace {

using namespace tumble;

constexpr std::size_t kFrames = 60;

std::filesystem::path demo_scene() {
  // tests/bench/ -> the repository root.
  return std::filesystem::path(__FILE__).parent_path().parent_path().parent_path() /
         "assets/scenes/t_handle_flip.json";
}

std::filesystem::path output_directory() {
  const auto dir = std::filesystem::temp_directory_path() / "tumble_bench_render_command";
  std::filesystem::create_directories(dir);
  return dir;
}

app::RenderOptions demo_options(const std::filesystem::path& output) {
  app::RenderOptions options;
  options.scene = demo_scene();
  options.output = output;
  options.size = "1280x720";
  options.frames = "0:" + std::to_string(kFrames);
  options.quiet = true;
  return options;
}

/// Runs kFrames frames per iteration, into `output` (empty: no sink).
void render_frames(benchmark::State& state, const std::string& output_name) {
  const std::filesystem::path output = output_directory() / output_name;
  const app::RenderPlan plan = app::plan_render(demo_options(output));
  media::SinkOptions sink_options;
  sink_options.width = plan.settings.width;
  sink_options.height = plan.settings.height;
  sink_options.fps = plan.settings.fps;
  tumble::Image image;
  for (auto _ : state) {
    // Set-up, untimed: meshes, GL context, the first overlay, the sink.
    state.PauseTiming();
    auto job = std::make_unique<app::RenderJob>(plan);
    job->advance_to(0);
    job->draw(image);
    std::unique_ptr<media::ImageSink> sink;
    if (!output_name.empty()) sink = media::open_image_sink(output, sink_options);
    state.ResumeTiming();

    for (std::size_t frame = 0; frame < kFrames; ++frame) {
      job->advance_to(frame);
      job->draw(image);
      if (sink) sink->write_taking(image);
    }
    if (sink) sink->finish();

    state.PauseTiming();
    job.reset();
    std::filesystem::remove_all(output);
    state.ResumeTiming();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kFrames));
}

void BM_RenderFrames(benchmark::State& state) {
  render_frames(state, "");
}
void BM_RenderToMp4(benchmark::State& state) {
  render_frames(state, "out.mp4");
}
void BM_RenderToPng(benchmark::State& state) {
  render_frames(state, "frames/");
}

void BM_RenderCommandMp4(benchmark::State& state) {
  const std::filesystem::path output = output_directory() / "command.mp4";
  const app::RenderOptions options = demo_options(output);
  for (auto _ : state) {
    std::ostringstream out;
    std::ostringstream err;
    const int status = app::run_render(options, out, err);
    if (status != 0) state.SkipWithError(err.str().c_str());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kFrames));
  std::filesystem::remove_all(output);
}

BENCHMARK(BM_RenderFrames)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(5);
BENCHMARK(BM_RenderToMp4)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(5);
BENCHMARK(BM_RenderToPng)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(5);
BENCHMARK(BM_RenderCommandMp4)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
