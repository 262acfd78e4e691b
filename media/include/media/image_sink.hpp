#pragma once
/// @file Where rendered frames go, chosen by the output name (media/output_kind.hpp):
///   "frames/"   (trailing slash or an existing directory) -> frames/frame_000000.png, ...
///   "out.mp4"   H.264 through an ffmpeg pipe
///   "out.webm"  VP9 through an ffmpeg pipe
///   "out.gif"   palette-optimised GIF through an ffmpeg pipe (palettegen + paletteuse)
/// (target tumble::media_sinks: PNG files need libpng.)
//
// Outputs are atomic: frames go to a temporary name in the target's directory, which finish()
// renames into place. Destroying a sink without finish(), or any failure, removes the temporary
// and leaves nothing under the final name; no descriptor or ffmpeg process outlives a failure.
//
// Errors, by whose they are to fix:
// - tumble::InputError, one line naming the path: what the user asked for cannot be written
//   (unknown extension, a directory that does not exist or cannot be written, a folder of other
//   files that would be replaced, an existing output that is not a regular file (a device, a
//   FIFO: never replaced; a link to a regular file is written through, the link stays), an
//   input, ffmpeg missing from PATH or not executable, ffmpeg failing on
//   the output, with its last stderr lines). The app reports these as bad input.
// - std::invalid_argument / std::logic_error: the caller's mistake (invalid SinkOptions, a
//   frame of the wrong size, writing to a finished sink).
// - std::runtime_error (not an InputError): the system failed us (no file descriptors for a
//   pipe, fork failing). The app reports these as internal errors.

#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "base/errors.hpp"
#include "base/image.hpp"
#include "media/output_kind.hpp"

namespace tumble::media {

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
  /// The files the output was made from (scene, meshes): an output that is one of them (by
  /// device and inode, through links too) is refused, never overwritten.
  std::vector<std::filesystem::path> inputs;
  /// When not empty, the output is one part of a sharded job and this text (its JSON manifest)
  /// is stored with it: as `part.json` in a PNG folder, as the container's `comment` tag of a
  /// video (read back with `ffprobe -show_entries format_tags=comment`).
  std::string part_manifest;
};

/// Consumes frames in order; see the file comment for the naming rules.
class ImageSink {
 public:
  virtual ~ImageSink() = default;
  /// Queues one frame (copied; returns once it is buffered). Throws std::invalid_argument for a
  /// frame of the wrong size, tumble::InputError when the output failed (ffmpeg stopped, with
  /// its last stderr lines; a PNG that could not be written), again on every later call, and
  /// std::logic_error once the sink is finished or abandoned.
  virtual void write(const Image& frame) = 0;
  /// Like write(), but may take the frame's pixels instead of copying them: `frame` keeps its
  /// size and gets a buffer of unspecified contents (possibly empty), ready to be drawn into
  /// again. The video sinks take; the default copies.
  virtual void write_taking(Image& frame) { write(frame); }
  /// Flushes, checks the encoder and moves the output to its final name. Throws
  /// tumble::InputError (one line naming the path, with ffmpeg's last stderr lines) on failure.
  /// Does nothing once finished (or failed).
  virtual void finish() = 0;
  /// Frames accepted so far.
  virtual std::size_t frames() const = 0;
};

/// Opens a sink, checking before any frame is rendered that the kind is known, the directory
/// is writable and (for videos) ffmpeg can be started. Throws tumble::InputError naming the
/// path for any of those, std::invalid_argument for invalid options (size, frame rate), and
/// std::runtime_error when the system cannot give a pipe or a process for ffmpeg.
std::unique_ptr<ImageSink> open_image_sink(const std::filesystem::path& target,
                                           const SinkOptions& options);

}  // namespace tumble::media
