#pragma once
// What both sinks are made of: the output's names (as asked, as replaced, as written until
// finished), the options, the queue of frames to the encoder threads and the count.

#include <cstddef>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "frame_queue.hpp"
#include "media/image_sink.hpp"

namespace tumble::media::detail {

class QueuedSink : public ImageSink {
 public:
  std::size_t frames() const override { return frames_; }

 protected:
  /// `what` names the sink in the caller's-mistake errors ("video sink", "PNG sink").
  QueuedSink(const std::filesystem::path& target, const SinkOptions& options, const char* what)
      : target_(target), options_(options), queue_(options.queue_frames), what_(what) {}

  /// Throws std::invalid_argument "WHAT 'TARGET': frame is WxH, expected WxH" for a frame of
  /// another size than the sink's (or whose pixels do not match its size).
  void check_size(const Image& frame) const {
    if (frame.width != options_.width || frame.height != options_.height ||
        frame.rgba.size() !=
            4 * static_cast<std::size_t>(frame.width) * static_cast<std::size_t>(frame.height)) {
      throw std::invalid_argument(std::string(what_) + " '" + target_.string() + "': frame is " +
                                  std::to_string(frame.width) + "x" + std::to_string(frame.height) +
                                  ", expected " + std::to_string(options_.width) + "x" +
                                  std::to_string(options_.height));
    }
  }

  std::filesystem::path target_;       // as the user named it
  std::filesystem::path destination_;  // what is replaced: target_, or a link's target
  std::filesystem::path temporary_;    // what is written until finish()
  SinkOptions options_;
  FrameQueue queue_;
  std::size_t frames_ = 0;  // accepted so far
  bool finished_ = false;   // finished, failed or abandoned: no more frames

 private:
  const char* what_;
};

}  // namespace tumble::media::detail
