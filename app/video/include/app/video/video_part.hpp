#pragma once
/// @file `--shard I/N` for `tumble render` and `tumble compare`: the frames of a shard and the
/// manifest its part carries (docs/merge.md).
///
/// The job's frames are those of `--frames A:B` (all of them without it); shard I of N takes
/// the I-th stretch of them, cut only where a key-frame interval (2 s of video, counted from A)
/// starts (app/farm/shard.hpp, aligned_range; tumble/video_encoding.hpp says why), so a video
/// segment starts where the whole video has its key frame. Every frame is drawn after
/// the simulation has observed every frame time from 0, so a shard's frames equal the same
/// frames of a full render. The manifest's job is the command, the scene and each mesh with a
/// digest of its bytes, and every setting that changes a frame or the video (resolved: the
/// scene's own render settings and the options on top), and the output format.

#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "app/video/render_job.hpp"

namespace tumble::app {

/// The settings of a video frame that go into a job: size, fps, time scale, anti-aliasing,
/// lod, font scale, overlay.
nlohmann::json frame_settings_json(const RenderSettings& settings);

/// For a sharded command (options.shard set): checks the output can be a part (GIF cannot),
/// cuts `frames` (the job's, A:B) to the shard's and returns the part's manifest as compact
/// JSON, with `job_options` (frame_settings_json plus the command's own, and the key-frame
/// interval at its fps) in the job. Returns ""
/// and leaves `frames` alone when not sharded. Throws InputError naming --shard.
std::string shard_video_frames(const VideoOptions& options, std::string_view command,
                               const SceneDescription& scene, std::size_t total_frames,
                               nlohmann::json job_options, FrameRange& frames);

}  // namespace tumble::app
