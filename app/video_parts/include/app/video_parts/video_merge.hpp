#pragma once
/// @file `tumble merge` for the parts of a sharded `tumble render` or `tumble compare`: PNG
/// frame folders and MP4/WebM segments joined into the whole video (docs/merge.md), and their
/// part kinds. Over farm and media only (no renderer), so that `tumble` links it.

#include <cstddef>
#include <filesystem>
#include <functional>
#include <vector>

#include "app/farm/part_kind.hpp"
#include "app/farm/part_manifest.hpp"

namespace tumble::app {

/// What a merge came to.
struct VideoMerge {
  std::size_t frames = 0;    ///< frames in the output
  bool copied = false;       ///< segments joined without re-encoding
  bool interrupted = false;  ///< `interrupted` said so; nothing was written
};

/// Checks that `parts` (their manifests read, kind render or compare) are one job's shards,
/// each exactly once, that their frames follow one another without a gap or an overlap, and
/// that each part holds the frames its manifest says; then writes `output`, atomically:
/// - `.mp4`/`.webm` from segments of that format: joined without re-encoding (ffmpeg's concat
///   demuxer, `-c copy`);
/// - `.mp4`/`.webm`/`.gif` from PNG parts (or from segments of another format): encoded once
///   with the settings `tumble render` uses for that extension;
/// - `DIR/` (PNG frames, their global numbers): from PNG parts the frames hard-linked (copied
///   across filesystems), from segments decoded.
/// Runs ffmpeg/ffprobe as child processes. Throws InputError naming the offending part (or the
/// output, or ffmpeg's last stderr lines); when `interrupted` returns true, ffmpeg is stopped,
/// nothing is left under the output name and the result says so.
VideoMerge merge_video_parts(const std::vector<NamedManifest>& parts,
                             const std::filesystem::path& output,
                             const std::function<bool()>& interrupted);

/// Checks one render or compare part on its own: its frames are its shard's stretch of the job's
/// and it holds them (a PNG folder: exactly those files; a segment: that many frames, counted by
/// ffprobe). Throws InputError naming the part.
void check_video_part_alone(const NamedManifest& part);

/// The kinds of `tumble render --shard` ("render") and `tumble compare --shard` ("compare")
/// parts: merged by merge_video_parts.
const PartKind& render_parts();
const PartKind& compare_parts();

}  // namespace tumble::app
