#pragma once
// Where rendered frames go, chosen by the output name:
//   "frames/"   (trailing slash or an existing directory) -> frames/frame_000000.png, ...
//   "out.mp4"   H.264 through an ffmpeg pipe
//   "out.webm"  VP9 through an ffmpeg pipe
//   "out.gif"   palette-optimised GIF through an ffmpeg pipe (palettegen + paletteuse)
// Outputs are atomic: frames go to a temporary name in the target's directory, which finish()
// renames into place. Destroying a sink without finish(), or any failure, removes the temporary
// and leaves nothing under the final name.

#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>

#include "render/image.hpp"

namespace tumble::render {

/// Kind of output, from its name.
enum class SinkKind { kPngSequence, kMp4, kWebm, kGif };

/// Frame size and rate of a sink.
struct SinkOptions {
  int width = 1280;
  int height = 720;
  double fps = 30.0;
  int png_threads = 2;           ///< PNG encoder threads (PNG sequences only)
  std::size_t queue_frames = 4;  ///< frames buffered between the render thread and the encoder
  /// Number of the first frame in a PNG sequence's file names (a frame range of a longer
  /// render keeps its absolute numbers: frame_000120.png ...).
  std::size_t first_index = 0;
};

/// Consumes frames in order; see the file comment for the naming rules.
class ImageSink {
 public:
  virtual ~ImageSink() = default;
  /// Queues one frame (copied; returns once it is buffered). Throws std::invalid_argument for a
  /// frame of the wrong size and std::runtime_error if the output already failed.
  virtual void write(const Image& frame) = 0;
  /// Flushes, checks the encoder and moves the output to its final name. Throws
  /// std::runtime_error (one line, with ffmpeg's last stderr line) on failure.
  virtual void finish() = 0;
  /// Frames accepted so far.
  virtual std::size_t frames() const = 0;
};

/// The kind of output a name asks for. Throws std::invalid_argument for anything else.
SinkKind sink_kind(const std::filesystem::path& target);

/// Opens a sink, checking before any frame is rendered that the kind is known, the directory
/// is writable and (for videos) ffmpeg can be started. Throws std::invalid_argument (unknown
/// kind, bad options) or std::runtime_error (filesystem, ffmpeg), naming the path.
std::unique_ptr<ImageSink> open_image_sink(const std::filesystem::path& target,
                                           const SinkOptions& options);

}  // namespace tumble::render
