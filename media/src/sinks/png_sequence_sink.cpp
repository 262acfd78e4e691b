// The PNG sequence sink: worker threads encode queued frames into a temporary folder.
#include "png_sequence_sink.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include "base/errors.hpp"
#include "base/file_checks.hpp"
#include "base/temporary_path.hpp"
#include "media/output_kind.hpp"
#include "media/png_io.hpp"
#include "queued_sink.hpp"

namespace tumble::media::detail {

namespace {

/// Writes `text` to `file` whole; throws tumble::InputError naming `target` on any failure.
void write_manifest(const std::filesystem::path& file, const std::string& text,
                    const std::filesystem::path& target) {
  std::FILE* out = std::fopen(file.c_str(), "wb");
  bool good = out != nullptr && std::fwrite(text.data(), 1, text.size(), out) == text.size();
  const int error = errno;
  if (out != nullptr && std::fclose(out) != 0) good = false;
  if (!good) {
    throw InputError("cannot write '" + (target / kFolderManifestName).string() +
                     "': " + std::strerror(error != 0 ? error : errno));
  }
}

class PngSequenceSink final : public QueuedSink {
 public:
  PngSequenceSink(const std::filesystem::path& target, const SinkOptions& options)
      : QueuedSink(target, options, "PNG sink") {
    // Check the destination before any frame is rendered.
    require_output_directory(target_);
    std::error_code error;
    if (std::filesystem::exists(target_, error)) {
      if (!std::filesystem::is_directory(target_, error)) {
        throw InputError("cannot write PNG frames to '" + target_.string() +
                         "': it exists and is not a directory");
      }
      if (!holds_only_frames(target_)) {
        throw InputError("refusing to replace '" + target_.string() +
                         "': it holds files other than frame_*.png");
      }
    }
    // A link to a folder is written through (the link stays); an input is never replaced.
    destination_ = checked_output(target_, options.inputs, /*directory=*/true);
    temporary_ = temporary_sibling(destination_);
    remove_stale_temporaries(destination_);
    std::filesystem::remove_all(temporary_, error);
    if (!std::filesystem::create_directory(temporary_, error)) {
      throw InputError("cannot write PNG frames to '" + target_.string() +
                       "': cannot create a directory in '" + output_directory(target_).string() +
                       "': " + error.message());
    }
    // Encoder threads.
    const int threads = options.png_threads < 1 ? 1 : options.png_threads;
    for (int i = 0; i < threads; ++i) workers_.emplace_back([this] { encode_loop(); });
  }

  ~PngSequenceSink() override {
    if (!finished_) abort();
  }

  void write(const Image& frame) override {
    check_size(frame);
    rethrow_failure();
    if (finished_ || !queue_.push(frame, options_.first_index + frames_)) {
      throw std::logic_error("PNG sink '" + target_.string() + "' is closed");
    }
    ++frames_;
  }

  void finish() override {
    if (finished_) return;
    // Drain the encoders, then swap the finished directory into place.
    join_workers();
    try {
      rethrow_failure();
      if (!options_.part_manifest.empty()) {
        write_manifest(temporary_ / kFolderManifestName, options_.part_manifest, target_);
      }
      const std::filesystem::path old = temporary_.string() + "-old";
      const bool replacing = std::filesystem::exists(destination_);
      if (replacing) std::filesystem::rename(destination_, old);
      std::filesystem::rename(temporary_, destination_);
      if (replacing) std::filesystem::remove_all(old);
    } catch (const std::filesystem::filesystem_error& e) {
      abort();
      const std::lock_guard lock(failure_mutex_);
      failure_ = std::make_exception_ptr(InputError("cannot move PNG frames into '" +
                                                    target_.string() + "': " + e.code().message()));
      std::rethrow_exception(failure_);
    } catch (...) {
      abort();
      throw;
    }
    finished_ = true;
  }

 private:
  void encode_loop() {
    FrameQueue::Item item;
    Image image;
    image.width = options_.width;
    image.height = options_.height;
    while (queue_.pop(item)) {
      image.rgba.swap(item.rgba);
      try {
        if (!failed()) write_png(temporary_ / frame_file_name(item.index), image, 1);
      } catch (...) {  // kept as thrown: tumble::InputError for a file that cannot be written
        std::lock_guard lock(failure_mutex_);
        if (!failure_) failure_ = std::current_exception();
      }
      queue_.recycle(std::move(image.rgba));
      image.rgba = {};
    }
  }

  bool failed() {
    std::lock_guard lock(failure_mutex_);
    return failure_ != nullptr;
  }

  /// The first failure of an encoder (or of finish), again for every later call.
  void rethrow_failure() {
    std::lock_guard lock(failure_mutex_);
    if (failure_) std::rethrow_exception(failure_);
  }

  void join_workers() {
    queue_.close();
    for (std::thread& worker : workers_) {
      if (worker.joinable()) worker.join();
    }
  }

  /// Stops the encoders and removes the temporary directory.
  void abort() {
    queue_.discard();
    join_workers();
    std::error_code ignored;
    std::filesystem::remove_all(temporary_, ignored);
    finished_ = true;
  }

  std::vector<std::thread> workers_;
  std::mutex failure_mutex_;
  std::exception_ptr failure_;
};

}  // namespace

std::unique_ptr<ImageSink> open_png_sequence(const std::filesystem::path& directory,
                                             const SinkOptions& options) {
  return std::make_unique<PngSequenceSink>(directory, options);
}

}  // namespace tumble::media::detail
