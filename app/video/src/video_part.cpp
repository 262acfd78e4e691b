// `--shard I/N` for render and compare: the shard's frames and its part manifest.
#include "app/video/video_part.hpp"

#include "app/farm/part_manifest.hpp"
#include "app/farm/shard.hpp"
#include "base/errors.hpp"
#include "media/image_sink.hpp"
#include "media/video_encoding.hpp"

namespace tumble::app {

namespace {

using nlohmann::json;

json antialiasing_json(const Antialiasing& antialiasing) {
  switch (antialiasing.mode) {
    case Antialiasing::Mode::kOff:
      return "off";
    case Antialiasing::Mode::kFxaa:
      return "fxaa";
    case Antialiasing::Mode::kMultisample:
      break;
  }
  return antialiasing.samples;
}

/// The part's format, as its job and payload name it: "png", "mp4" or "webm".
std::string part_format(const std::filesystem::path& output) {
  switch (media::sink_kind(output)) {
    case media::SinkKind::kPngSequence:
      return "png";
    case media::SinkKind::kMp4:
      return "mp4";
    case media::SinkKind::kWebm:
      return "webm";
    case media::SinkKind::kGif:
      break;
  }
  throw InputError(
      "--shard: GIF output cannot be sharded (a GIF cannot be joined without re-encoding); shard "
      "to PNG frames (-o DIR/) or .mp4/.webm segments and make the GIF with tumble merge PART... "
      "-o OUT.gif");
}

/// The scene and each mesh it reads, with a digest of its bytes.
json inputs_json(const SceneDescription& scene) {
  json inputs = json::array();
  for (const std::filesystem::path& file : scene_inputs(scene)) {
    inputs.push_back({{"path", file.string()}, {"digest", file_digest(file)}});
  }
  return inputs;
}

}  // namespace

json frame_settings_json(const RenderSettings& settings) {
  return json{{"size", {settings.width, settings.height}},
              {"fps", settings.fps},
              {"time_scale", settings.time_scale},
              {"aa", antialiasing_json(settings.antialiasing)},
              {"lod", settings.lod},
              {"font_scale", settings.font_scale},
              {"overlay", settings.show.overlay}};
}

std::string shard_video_frames(const VideoOptions& options, std::string_view command,
                               const SceneDescription& scene, std::size_t total_frames,
                               json job_options, FrameRange& frames) {
  if (!options.shard) return "";
  const Shard shard = parse_shard(*options.shard);
  const std::string format = part_format(options.output);
  const FrameRange job_frames = frames;
  const std::size_t total = job_frames.end - job_frames.first;
  // A video segment starts on a key frame of the whole video; PNG frames on any frame.
  const std::size_t interval =
      format == "png" ? 1 : media::keyframe_interval(job_options.at("fps").get<double>());
  const ItemRange range = aligned_range(total, interval, shard);
  if (range.size() == 0) {
    std::string intervals;
    if (interval > 1) {
      const std::size_t count = (total + interval - 1) / interval;
      intervals = " in " + std::to_string(count) + " key-frame interval" + (count == 1 ? "" : "s") +
                  " of " + std::to_string(interval) +
                  " (2 s of video; a segment starts on a key frame)";
    }
    throw InputError("--shard " + shard.text() + ": the job has " + std::to_string(total) +
                     (total == 1 ? " frame" : " frames") + intervals + ", too few for " +
                     std::to_string(shard.count) + " shards");
  }
  frames = {job_frames.first + range.begin, job_frames.first + range.end};

  job_options["frames"] = {job_frames.first, job_frames.end};
  job_options["keyframe_interval"] = interval;
  job_options["total_frames"] = total_frames;
  PartManifest manifest;
  manifest.kind = std::string(command);
  manifest.tumble_version = TUMBLE_VERSION;
  manifest.job = json{{"command", std::string(command)},
                      {"inputs", inputs_json(scene)},
                      {"options", std::move(job_options)},
                      {"output", format}};
  manifest.shard = shard;
  manifest.total = total;
  manifest.split = ShardSplit::kContiguous;
  manifest.payload = json{{"frames", {frames.first, frames.end}}, {"format", format}};
  return manifest_json(manifest).dump();
}

}  // namespace tumble::app
