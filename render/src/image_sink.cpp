#include "render/image_sink.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <stdexcept>
#include <system_error>

#include "base/errors.hpp"
#include "ffmpeg_sink.hpp"
#include "png_sequence_sink.hpp"

namespace tumble::render {

namespace {

/// The path without trailing slashes ("frames/" -> "frames").
std::filesystem::path without_trailing_slash(const std::filesystem::path& target) {
  std::string text = target.string();
  while (text.size() > 1 && text.back() == '/') text.pop_back();
  return text;
}

}  // namespace

SinkKind sink_kind(const std::filesystem::path& target) {
  const std::string text = target.string();
  std::error_code error;
  if (!text.empty() && (text.back() == '/' || std::filesystem::is_directory(target, error))) {
    return SinkKind::kPngSequence;
  }
  std::string extension = target.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == ".mp4") return SinkKind::kMp4;
  if (extension == ".webm") return SinkKind::kWebm;
  if (extension == ".gif") return SinkKind::kGif;
  throw InputError("unknown output '" + text +
                   "': expected a directory ending in '/' (PNG frames) or a .mp4, .webm or .gif "
                   "file");
}

std::unique_ptr<ImageSink> open_image_sink(const std::filesystem::path& target,
                                           const SinkOptions& options) {
  const SinkKind kind = sink_kind(target);
  if (options.width <= 0 || options.height <= 0 || !(options.fps > 0.0) ||
      !std::isfinite(options.fps)) {
    throw std::invalid_argument("output '" + target.string() + "': invalid size " +
                                std::to_string(options.width) + "x" +
                                std::to_string(options.height) + " or frame rate");
  }
  if (kind == SinkKind::kPngSequence) {
    return detail::open_png_sequence(without_trailing_slash(target), options);
  }
  return detail::open_ffmpeg_sink(target, kind, options);
}

}  // namespace tumble::render
