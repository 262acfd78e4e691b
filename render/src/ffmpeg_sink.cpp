#include "ffmpeg_sink.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <stdexcept>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include "base/errors.hpp"
#include "base/file_checks.hpp"
#include "base/video_encoding.hpp"
#include "frame_queue.hpp"
#include "output_paths.hpp"
#include "unique_fd.hpp"

extern char** environ;

namespace tumble::render::detail {

namespace {

/// Encoder arguments per kind (after the raw-video input) at `fps`.
std::vector<std::string> encoder_arguments(SinkKind kind, double fps) {
  switch (kind) {
    case SinkKind::kMp4:
      return ffmpeg_encoder_arguments("mp4", fps);
    case SinkKind::kWebm:
      return ffmpeg_encoder_arguments("webm", fps);
    case SinkKind::kGif:
      return ffmpeg_encoder_arguments("gif", fps);
    case SinkKind::kPngSequence:
      break;
  }
  throw std::logic_error("ffmpeg sink: not a video kind");
}

/// The last two non-empty lines of ffmpeg's stderr on one line (libx264, say, names the
/// cause on the line before ffmpeg's generic "Error initializing output stream").
std::string last_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t begin = 0;
  while (begin < text.size()) {
    std::size_t end = text.find_first_of("\r\n", begin);
    if (end == std::string::npos) end = text.size();
    if (end > begin) lines.push_back(text.substr(begin, end - begin));
    begin = end + 1;
  }
  if (lines.empty()) return "no message on stderr";
  if (lines.size() == 1) return lines.back();
  return lines[lines.size() - 2] + " / " + lines.back();
}

/// posix_spawn file actions, destroyed with their owner.
class SpawnActions {
 public:
  SpawnActions() {
    if (const int error = posix_spawn_file_actions_init(&actions_); error != 0) {
      throw std::runtime_error(std::string("cannot start ffmpeg: ") + std::strerror(error));
    }
  }
  ~SpawnActions() { posix_spawn_file_actions_destroy(&actions_); }
  SpawnActions(const SpawnActions&) = delete;
  SpawnActions& operator=(const SpawnActions&) = delete;
  posix_spawn_file_actions_t* get() { return &actions_; }

 private:
  posix_spawn_file_actions_t actions_;
};

/// Whether a posix_spawnp error is the user's to fix: no ffmpeg on PATH, or one that cannot be
/// executed. Anything else (fork failing for want of memory or processes) is the system's.
bool spawn_error_is_input(int error) {
  return error == ENOENT || error == EACCES || error == ENOEXEC || error == ENOTDIR ||
         error == ELOOP || error == ENAMETOOLONG;
}

/// Writes all of `size` bytes; false on a broken pipe or other error.
bool write_all(int fd, const std::uint8_t* data, std::size_t size) {
  while (size > 0) {
    const ssize_t written = ::write(fd, data, size);
    if (written < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    data += written;
    size -= static_cast<std::size_t>(written);
  }
  return true;
}

class FfmpegSink final : public ImageSink {
 public:
  FfmpegSink(const std::filesystem::path& target, SinkKind kind, const SinkOptions& options)
      : target_(target), options_(options), queue_(options.queue_frames) {
    // The destination must be writable before any frame is rendered, and be a new name or a
    // regular file (through a link: the link's target), never a device or an input.
    require_output_directory(target_);
    destination_ = checked_output(target_, options.inputs);
    temporary_ = temporary_sibling(destination_);
    remove_stale_temporaries(destination_);
    if (!UniqueFd(::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644))) {
      throw InputError("cannot write '" + target_.string() + "': directory '" +
                       output_directory(target_).string() + "': " + std::strerror(errno));
    }
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

  std::size_t frames() const override { return frames_; }

 private:
  void check_writable(const Image& frame) {
    if (frame.width != options_.width || frame.height != options_.height ||
        frame.rgba.size() !=
            4 * static_cast<std::size_t>(frame.width) * static_cast<std::size_t>(frame.height)) {
      throw std::invalid_argument("video sink '" + target_.string() + "': frame is " +
                                  std::to_string(frame.width) + "x" + std::to_string(frame.height) +
                                  ", expected " + std::to_string(options_.width) + "x" +
                                  std::to_string(options_.height));
    }
    if (!failure_.empty()) throw InputError(failure_);
    if (finished_) throw std::logic_error("video sink '" + target_.string() + "' is closed");
    if (pipe_broken()) fail();
  }

  /// Starts ffmpeg reading raw RGBA on stdin, stderr captured, writing the temporary file.
  void spawn(SinkKind kind) {
    char size[64];
    std::snprintf(size, sizeof size, "%dx%d", options_.width, options_.height);
    std::string rate = ffmpeg_rate(options_.fps);
    std::vector<std::string> arguments = {
        "ffmpeg", "-hide_banner", "-nostdin", "-nostats", "-loglevel", "error",
        "-y",     "-f",           "rawvideo", "-pix_fmt", "rgba",      "-s",
        size,     "-r",           rate,       "-i",       "-"};
    for (std::string& argument : encoder_arguments(kind, options_.fps))
      arguments.push_back(std::move(argument));
    if (!options_.part_manifest.empty()) {
      // A shard's segment says what it is in its container (MP4 ilst, Matroska tags).
      arguments.insert(arguments.end(), {"-metadata", "comment=" + options_.part_manifest});
    }
    arguments.push_back(temporary_.string());
    std::vector<char*> argv;
    for (std::string& argument : arguments) argv.push_back(argument.data());
    argv.push_back(nullptr);

    Pipe in;
    Pipe err;
    if (!make_pipe(in) || !make_pipe(err)) {
      throw std::runtime_error("cannot write '" + target_.string() +
                               "': cannot start ffmpeg: pipe: " + std::strerror(errno));
    }
    SpawnActions actions;
    posix_spawn_file_actions_adddup2(actions.get(), in.read.get(), STDIN_FILENO);
    posix_spawn_file_actions_addopen(actions.get(), STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_adddup2(actions.get(), err.write.get(), STDERR_FILENO);
    pid_t child = -1;
    const int spawned =
        ::posix_spawnp(&child, "ffmpeg", actions.get(), nullptr, argv.data(), environ);
    if (spawned != 0) {
      const std::string message =
          "cannot write '" + target_.string() + "': " +
          (spawned == ENOENT ? std::string("ffmpeg not found on PATH")
                             : "cannot start ffmpeg: " + std::string(std::strerror(spawned)));
      if (spawn_error_is_input(spawned)) throw InputError(message);
      throw std::runtime_error(message);
    }
    child_ = child;
    // A frame is ~3.7 MB at 720p: a 1 MiB pipe (the default is 64 KiB) takes it in 4 writes
    // instead of ~56 wake-ups of ffmpeg's reader. Best effort; the default still works.
    ::fcntl(in.write.get(), F_SETPIPE_SZ, 1 << 20);
    stdin_ = std::move(in.write);
    stderr_ = std::move(err.read);
    // The child's ends (in.read, err.write) close here, so ffmpeg sees EOF and we see its exit.
  }

  /// Keeps the tail of ffmpeg's stderr for error messages.
  void read_stderr() {
    char buffer[4096];
    for (;;) {
      const ssize_t n = ::read(stderr_.get(), buffer, sizeof buffer);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;
      std::lock_guard lock(mutex_);
      stderr_text_.append(buffer, static_cast<std::size_t>(n));
      if (stderr_text_.size() > 16384) stderr_text_.erase(0, stderr_text_.size() - 8192);
    }
    stderr_.reset();
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
      if (!pipe_broken() && !write_all(stdin_.get(), item.rgba.data(), item.rgba.size())) {
        const timespec zero{0, 0};
        sigtimedwait(&pipe_signal, nullptr, &zero);  // consume the pending SIGPIPE
        std::lock_guard lock(mutex_);
        pipe_broken_ = true;
      }
      queue_.recycle(std::move(item.rgba));
      item.rgba = {};
    }
  }

  bool pipe_broken() {
    std::lock_guard lock(mutex_);
    return pipe_broken_;
  }

  /// Ends the stream (or kills ffmpeg) and returns its exit status (-1 if killed).
  int stop(bool kill_child) {
    if (kill_child) queue_.discard();
    queue_.close();
    if (writer_.joinable()) writer_.join();
    stdin_.reset();
    if (child_ <= 0) return -1;
    if (kill_child) ::kill(child_, SIGKILL);
    int status = 0;
    while (::waitpid(child_, &status, 0) < 0 && errno == EINTR) {
    }
    child_ = -1;
    if (stderr_reader_.joinable()) stderr_reader_.join();
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
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

  std::filesystem::path target_;
  std::filesystem::path destination_;  // what is replaced: target_, or a link's target
  std::filesystem::path temporary_;
  SinkOptions options_;
  FrameQueue queue_;
  pid_t child_ = -1;
  UniqueFd stdin_;   // frames to ffmpeg
  UniqueFd stderr_;  // ffmpeg's messages; read and closed by stderr_reader_
  std::thread writer_;
  std::thread stderr_reader_;
  std::mutex mutex_;
  std::string stderr_text_;
  bool pipe_broken_ = false;
  std::size_t frames_ = 0;
  bool finished_ = false;
  std::string failure_;  // why the output failed, repeated by later writes
};

}  // namespace

std::unique_ptr<ImageSink> open_ffmpeg_sink(const std::filesystem::path& target, SinkKind kind,
                                            const SinkOptions& options) {
  return std::make_unique<FfmpegSink>(target, kind, options);
}

}  // namespace tumble::render::detail
