// Opening a sink: the kind from the name, the options checked.
#include "media/image_sink.hpp"

#include <cmath>
#include <stdexcept>

#include "base/errors.hpp"
#include "ffmpeg_sink.hpp"
#include "png_sequence_sink.hpp"

namespace tumble::media {

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

}  // namespace tumble::media
