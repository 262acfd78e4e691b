#pragma once
/// @file The joiner: stretches of one video made apart (PNG frame folders or MP4/WebM segments)
/// joined into the whole (a video or a folder of frames), as `tumble merge` does with the parts of
/// a sharded render. It knows nothing of parts or manifests: the caller says which frames each
/// piece holds, after checking that.
///
/// How, by what is joined into what:
/// - segments into a video of their own format: ffmpeg's concat demuxer, `-c copy` (no
///   re-encoding; the segments must start on key frames, media/video_encoding.hpp);
/// - PNG frames, or segments of another format, into a video: encoded once with the settings a
///   sink uses for that extension (media/video_encoding.hpp);
/// - PNG frames into a folder: hard links (copies across filesystems), no ffmpeg;
/// - segments into a folder: decoded into PNG frames.
/// The output keeps the whole video's frame numbers (frame_000120.png ...).

#include <cstddef>
#include <filesystem>
#include <functional>
#include <vector>

#include "media/output_kind.hpp"

namespace tumble::media {

/// One stretch of the frames: a folder of PNG frames (frame_file_name of each frame's number in
/// the whole video) or a video segment, holding frames [first, end).
struct JoinPiece {
  std::filesystem::path path;
  std::size_t first = 0;
  std::size_t end = 0;
};

/// Pieces that make one video: in order, each starting where the one before ends.
struct JoinInput {
  SinkKind format = SinkKind::kPngSequence;  ///< of every piece: kPngSequence, kMp4 or kWebm
  double fps = 30.0;
  std::vector<JoinPiece> pieces;
};

/// What a join came to.
struct JoinResult {
  std::size_t frames = 0;    ///< frames in the output
  bool copied = false;       ///< segments joined without re-encoding
  bool interrupted = false;  ///< `interrupted` said so; nothing was written
};

/// Writes `output` (a .mp4, .webm or .gif file, or a folder DIR/) from `input`'s pieces,
/// atomically: everything is made in a staging folder beside the output (`.OUT.tmp-PID`) and
/// renamed into place at the end, so that a failure or an interruption leaves nothing under the
/// output's name. The output may be a new name, a regular file or (for a folder) a folder of
/// frames, never one of the pieces. Runs ffmpeg as a child process. Throws tumble::InputError
/// naming the output (unknown kind, not writable, ffmpeg failing: its last stderr lines); when
/// `interrupted` returns true, ffmpeg is stopped and the result says so.
JoinResult join_video(const JoinInput& input, const std::filesystem::path& output,
                      const std::function<bool()>& interrupted = {});

}  // namespace tumble::media
