// The encoder's own speed against `tumble render` end to end, on the same frames (the default
// demo, t_handle_flip, 1280x720 at 30 fps, kFrames frames):
//  - BM_FfmpegAlone: the frames, rendered beforehand and held in memory, piped into ffmpeg
//    with the MP4 sink's arguments (raw RGBA in, tumble/video_encoding.hpp's libx264 settings
//    out): the floor;
//  - BM_EndToEndMp4: simulate, draw, read back and encode through the MP4 sink, as
//    `tumble render` does (write_taking, finish() included).
// The ratio of the two wall times is what the render side costs on top of the encoder.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "app/commands/render_command.hpp"
#include "media/image_sink.hpp"
#include "media/video_encoding.hpp"

namespace {

using namespace tumble;

constexpr std::size_t kFrames = 120;

std::filesystem::path output_directory() {
  const auto dir = std::filesystem::temp_directory_path() / "tumble_bench_encode";
  std::filesystem::create_directories(dir);
  return dir;
}

app::RenderPlan demo_plan(const std::filesystem::path& output) {
  app::RenderOptions options;
  options.scene = std::filesystem::path(__FILE__).parent_path().parent_path().parent_path() /
                  "assets/scenes/t_handle_flip.json";
  options.output = output;
  options.size = "1280x720";
  options.frames = "0:" + std::to_string(kFrames);
  options.quiet = true;
  return app::plan_render(options);
}

void BM_FfmpegAlone(benchmark::State& state) {
  const auto output = output_directory() / "alone.mp4";
  const app::RenderPlan plan = demo_plan(output);
  std::vector<tumble::Image> frames(kFrames);
  {
    app::RenderJob job(plan);
    for (std::size_t frame = 0; frame < kFrames; ++frame) {
      job.advance_to(frame);
      job.draw(frames[frame]);
    }
  }
  // The MP4 sink's command line (media/src/sinks/ffmpeg_sink.cpp), its encoder settings included.
  std::string command =
      "ffmpeg -hide_banner -nostdin -nostats -loglevel error -y -f rawvideo -pix_fmt rgba -s " +
      std::to_string(plan.settings.width) + "x" + std::to_string(plan.settings.height) + " -r " +
      media::ffmpeg_rate(plan.settings.fps) + " -i -";
  for (const std::string& argument : media::ffmpeg_encoder_arguments("mp4", plan.settings.fps)) {
    command += " '" + argument + "'";
  }
  command += " '" + output.string() + "'";
  for (auto _ : state) {
    FILE* pipe = ::popen(command.c_str(), "w");
    if (pipe == nullptr) {
      state.SkipWithError("cannot start ffmpeg");
      break;
    }
    for (const tumble::Image& image : frames) {
      std::fwrite(image.rgba.data(), 1, image.rgba.size(), pipe);
    }
    if (::pclose(pipe) != 0) state.SkipWithError("ffmpeg failed");
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kFrames));
  std::filesystem::remove(output);
}

void BM_EndToEndMp4(benchmark::State& state) {
  const auto output = output_directory() / "end_to_end.mp4";
  const app::RenderPlan plan = demo_plan(output);
  media::SinkOptions sink_options;
  sink_options.width = plan.settings.width;
  sink_options.height = plan.settings.height;
  sink_options.fps = plan.settings.fps;
  tumble::Image image;
  for (auto _ : state) {
    // Untimed: meshes, GL context, the first overlay (ImGui's font atlas).
    state.PauseTiming();
    auto job = std::make_unique<app::RenderJob>(plan);
    job->advance_to(0);
    job->draw(image);
    state.ResumeTiming();
    auto sink = media::open_image_sink(output, sink_options);
    for (std::size_t frame = 0; frame < kFrames; ++frame) {
      job->advance_to(frame);
      job->draw(image);
      sink->write_taking(image);
    }
    sink->finish();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kFrames));
  std::filesystem::remove(output);
}

BENCHMARK(BM_FfmpegAlone)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);
BENCHMARK(BM_EndToEndMp4)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
