// The video sink: a writer thread pipes queued frames into ffmpeg's standard input, a reader
// thread keeps the tail of its standard error for messages (base/process.hpp starts it).
//
// The frames go into the pipe by vmsplice(2): the pipe takes references to the frame's pages
// instead of a copy, and ffmpeg's read() copies them out, one copy of each frame instead of two
// and no pipe pages to allocate and clear: this halved the default demo's system time
// (docs/performance.md). The price: a frame's memory must stay unchanged until ffmpeg has read
// it. A pipe holds at most capacity / page size buffers of at most a page each, and gives them
// to the reader in order; so once `capacity` more bytes have gone in after a frame, none of
// that frame is left in it. The writer keeps each frame until then (and every frame until
// ffmpeg has exited), and only then hands its buffer back to be drawn into again.
#include "ffmpeg_sink.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/uio.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <deque>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include "base/errors.hpp"
#include "base/file_checks.hpp"
#include "base/process.hpp"
#include "base/temporary_path.hpp"
#include "media/output_kind.hpp"
#include "media/video_encoding.hpp"
#include "queued_sink.hpp"

namespace tumble::media::detail {

namespace {

/// Puts all of `size` bytes into the pipe `fd`, by vmsplice while `splice` (false for good
/// once the kernel refuses it: then by write); false on a broken pipe or other error.
bool write_all(int fd, const std::uint8_t* data, std::size_t size, bool& splice) {
  while (size > 0) {
    ssize_t written = 0;
    if (splice) {
      iovec pages{const_cast<std::uint8_t*>(data), size};
      written = ::vmsplice(fd, &pages, 1, 0);
      if (written < 0 && (errno == EINVAL || errno == ENOSYS || errno == EPERM)) {
        splice = false;
        continue;
      }
    } else {
      written = ::write(fd, data, size);
    }
    if (written < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    data += written;
    size -= static_cast<std::size_t>(written);
  }
  return true;
}

/// Checks that a file can be created in the target's folder (before any frame is rendered).
void require_writable(const std::filesystem::path& temporary, const std::filesystem::path& target) {
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) {
    throw InputError("cannot write '" + target.string() + "': directory '" +
                     output_directory(target).string() + "': " + std::strerror(errno));
  }
  ::close(fd);
}

class FfmpegSink final : public QueuedSink {
 public:
  FfmpegSink(const std::filesystem::path& target, SinkKind kind, const SinkOptions& options)
      : QueuedSink(target, options, "video sink") {
    // The destination must be writable before any frame is rendered, and be a new name or a
    // regular file (through a link: the link's target), never a device or an input.
    require_output_directory(target_);
    destination_ = checked_output(target_, options.inputs);
    temporary_ = temporary_sibling(destination_);
    remove_stale_temporaries(destination_);
    require_writable(temporary_, target_);
    // From here on a failure stops whatever started (ffmpeg, the threads), closes the pipes
    // and removes the temporary file before it propagates.
    try {
      spawn(kind);
      stderr_reader_ = std::thread([this] { read_stderr(); });
      writer_ = std::thread([this] { write_loop(); });
    } catch (...) {
      abort();
      throw;
    }
  }

  ~FfmpegSink() override {
    if (!finished_) abort();
  }

  void write(const Image& frame) override {
    check_writable(frame);
    queue_.push(frame, frames_);
    ++frames_;
  }

  void write_taking(Image& frame) override {
    check_writable(frame);
    queue_.push_taking(frame.rgba, frames_);
    ++frames_;
  }

  void finish() override {
    if (finished_) return;
    const int status = stop(/*kill_child=*/false);
    if (status != 0 || pipe_broken_) fail_after_stop(status);
    std::error_code error;
    std::filesystem::rename(temporary_, destination_, error);
    if (error) {
      std::filesystem::remove(temporary_, error);
      finished_ = true;
      failure_ = "cannot move video into '" + target_.string() + "': " + error.message();
      throw InputError(failure_);
    }
    finished_ = true;
  }

 private:
  void check_writable(const Image& frame) {
    check_size(frame);
    if (!failure_.empty()) throw InputError(failure_);
    if (finished_) throw std::logic_error("video sink '" + target_.string() + "' is closed");
    if (pipe_broken()) fail();
  }

  /// Starts ffmpeg reading raw RGBA on stdin, stderr captured, writing the temporary file.
  void spawn(SinkKind kind) {
    char size[64];
    std::snprintf(size, sizeof size, "%dx%d", options_.width, options_.height);
    std::vector<std::string> arguments = {"ffmpeg",
                                          "-hide_banner",
                                          "-nostdin",
                                          "-nostats",
                                          "-loglevel",
                                          "error",
                                          "-y",
                                          "-f",
                                          "rawvideo",
                                          "-pix_fmt",
                                          "rgba",
                                          "-s",
                                          size,
                                          "-r",
                                          ffmpeg_rate(options_.fps),
                                          "-i",
                                          "-"};
    for (std::string& argument : ffmpeg_encoder_arguments(format_name(kind), options_.fps)) {
      arguments.push_back(std::move(argument));
    }
    if (!options_.part_manifest.empty()) {
      // A shard's segment says what it is in its container (MP4 ilst, Matroska tags).
      arguments.insert(arguments.end(), {"-metadata", "comment=" + options_.part_manifest});
    }
    arguments.push_back(temporary_.string());
    try {
      child_.emplace(arguments, ChildStream::pipe(), ChildStream::null_device(),
                     ChildStream::pipe());
    } catch (const InputError& error) {
      throw InputError("cannot write '" + target_.string() + "': " + error.what());
    } catch (const std::runtime_error& error) {
      throw std::runtime_error("cannot write '" + target_.string() + "': " + error.what());
    }
    // A frame is ~3.7 MB at 720p: a 1 MiB pipe (the default is 64 KiB) takes it in 4 writes
    // instead of ~56 wake-ups of ffmpeg's reader. Best effort; the default still works. Frames
    // are spliced only when the capacity is known (see above).
    ::fcntl(child_->input(), F_SETPIPE_SZ, 1 << 20);
    const int capacity = ::fcntl(child_->input(), F_GETPIPE_SZ);
    pipe_capacity_ = capacity > 0 ? static_cast<std::size_t>(capacity) : 0;
    splice_ = capacity > 0;
  }

  /// Keeps the tail of ffmpeg's stderr for error messages.
  void read_stderr() {
    char buffer[4096];
    for (;;) {
      const ssize_t n = ::read(child_->error(), buffer, sizeof buffer);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;
      std::lock_guard lock(mutex_);
      stderr_text_.append(buffer, static_cast<std::size_t>(n));
      if (stderr_text_.size() > 16384) stderr_text_.erase(0, stderr_text_.size() - 8192);
    }
  }

  /// Pipes queued frames into ffmpeg; after a broken pipe, drains the queue without writing.
  void write_loop() {
    // A broken pipe must be an error return here, not a process-killing SIGPIPE.
    sigset_t pipe_signal;
    sigemptyset(&pipe_signal);
    sigaddset(&pipe_signal, SIGPIPE);
    pthread_sigmask(SIG_BLOCK, &pipe_signal, nullptr);
    FrameQueue::Item item;
    while (queue_.pop(item)) {
      if (!pipe_broken() &&
          !write_all(child_->input(), item.rgba.data(), item.rgba.size(), splice_)) {
        const timespec zero{0, 0};
        sigtimedwait(&pipe_signal, nullptr, &zero);  // consume the pending SIGPIPE
        std::lock_guard lock(mutex_);
        pipe_broken_ = true;
      }
      // Kept until the pipe can hold none of it (see above), then drawn into again.
      bytes_in_ += item.rgba.size();
      in_pipe_.push_back({std::move(item.rgba), bytes_in_});
      item.rgba = {};
      while (!in_pipe_.empty() && bytes_in_ - in_pipe_.front().end >= pipe_capacity_) {
        queue_.recycle(std::move(in_pipe_.front().rgba));
        in_pipe_.pop_front();
      }
    }
  }

  bool pipe_broken() {
    std::lock_guard lock(mutex_);
    return pipe_broken_;
  }

  /// Ends the stream (or kills ffmpeg) and returns its exit status (-1 if a signal ended it).
  int stop(bool kill_child) {
    if (kill_child) queue_.discard();
    queue_.close();
    if (writer_.joinable()) writer_.join();
    if (!child_) return -1;
    child_->close_input();
    const ChildExit exit = kill_child ? child_->kill() : child_->wait();
    if (stderr_reader_.joinable()) stderr_reader_.join();
    child_.reset();
    in_pipe_.clear();  // ffmpeg has read (or will never read) every frame
    return exit.status;
  }

  /// ffmpeg stopped reading: collect its exit status and message, clean up, throw.
  [[noreturn]] void fail() { fail_after_stop(stop(/*kill_child=*/false)); }

  [[noreturn]] void fail_after_stop(int status) {
    std::error_code ignored;
    std::filesystem::remove(temporary_, ignored);
    finished_ = true;
    std::string message;
    {
      std::lock_guard lock(mutex_);
      message = last_lines(stderr_text_);
    }
    failure_ = "ffmpeg failed writing '" + target_.string() + "' (exit status " +
               std::to_string(status) + "): " + message;
    throw InputError(failure_);
  }

  void abort() {
    stop(/*kill_child=*/true);
    std::error_code ignored;
    std::filesystem::remove(temporary_, ignored);
    finished_ = true;
  }

  std::optional<ChildProcess> child_;  // ffmpeg, with its stdin and stderr piped
  std::thread writer_;
  std::thread stderr_reader_;
  std::mutex mutex_;
  std::string stderr_text_;
  bool pipe_broken_ = false;
  std::string failure_;  // why the output failed, repeated by later writes
  /// The writer's (until joined): frames ffmpeg may not have read yet, oldest first, each with
  /// the count of bytes_in_ once it had gone in.
  struct InPipe {
    std::vector<std::uint8_t> rgba;
    std::size_t end = 0;
  };
  std::deque<InPipe> in_pipe_;
  std::size_t bytes_in_ = 0;       // put into the pipe so far
  std::size_t pipe_capacity_ = 0;  // bytes; 0: unknown (then frames are written, not spliced)
  bool splice_ = false;
};

}  // namespace

std::unique_ptr<ImageSink> open_ffmpeg_sink(const std::filesystem::path& target, SinkKind kind,
                                            const SinkOptions& options) {
  return std::make_unique<FfmpegSink>(target, kind, options);
}

}  // namespace tumble::media::detail
