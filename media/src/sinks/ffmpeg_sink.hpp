#pragma once
// Video sinks: raw RGBA frames piped into an ffmpeg child process that encodes to a temporary
// file, renamed to the target when ffmpeg exits cleanly.

#include <memory>

#include "media/image_sink.hpp"

namespace tumble::media::detail {

/// `kind` is kMp4, kWebm or kGif.
std::unique_ptr<ImageSink> open_ffmpeg_sink(const std::filesystem::path& target, SinkKind kind,
                                            const SinkOptions& options);

}  // namespace tumble::media::detail
