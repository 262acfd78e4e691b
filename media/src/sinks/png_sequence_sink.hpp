#pragma once
// PNG sequence sink: frame_000000.png, ... encoded by worker threads into a temporary
// directory that finish() renames to the target.

#include <memory>

#include "media/image_sink.hpp"

namespace tumble::media::detail {

/// `directory` has no trailing slash.
std::unique_ptr<ImageSink> open_png_sequence(const std::filesystem::path& directory,
                                             const SinkOptions& options);

}  // namespace tumble::media::detail
