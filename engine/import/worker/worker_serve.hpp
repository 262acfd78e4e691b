#pragma once
// The import worker's side (worker_protocol.hpp): the loop a worker program runs, serving one
// request at a time with the task it names. tumble-import serves assimp's reading
// (engine/import/worker/); the tests build a worker of their own with tasks that crash, loop or
// allocate, to check that the parent refuses each in one line.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace tumble::engine::detail {

/// Writes a task's answer into the worker's memory file, buffered; a write that fails (no
/// memory or file space left) ends the worker with kCannotAnswer. Offsets count from the start
/// of the payload, which is 8-byte aligned in the parent's mapping.
class AnswerWriter {
 public:
  explicit AnswerWriter(int fd);
  AnswerWriter(const AnswerWriter&) = delete;
  AnswerWriter& operator=(const AnswerWriter&) = delete;

  void bytes(const void* data, std::size_t size);
  template <typename T>
  void value(const T& item) {
    bytes(&item, sizeof item);
  }
  /// A text: u64 length, then its bytes.
  void text(std::string_view item);
  /// Zero bytes up to the next multiple of `alignment`.
  void align(std::size_t alignment);
  /// Writes out what is buffered.
  void flush();

 private:
  int fd_;
  std::uint64_t offset_ = 0;
  std::string buffer_;
};

/// What a worker does for one request: reads the request's texts, writes its answer's payload.
/// An InputError it throws reaches the parent word for word; std::bad_alloc as "needs more
/// memory"; anything else as a failure with its message.
using WorkerTask = void (*)(const std::vector<std::string>& request, AnswerWriter& out);

struct WorkerTaskEntry {
  std::string_view name;
  WorkerTask task;
};

/// True when the program was started as an import worker (argv[1] is kWorkerFlag).
bool started_as_worker(int argc, char** argv);

/// The worker's main loop: checks that its parent is still the process that started it (and
/// arranges to end with the thread that did, PR_SET_PDEATHSIG), restores the default action of
/// the signals that end it and turns off core files, then serves requests on kWorkerSocket
/// until it closes, each under its CPU-time and memory budget. Returns the exit status.
int serve_import_requests(int argc, char** argv, std::span<const WorkerTaskEntry> tasks);

}  // namespace tumble::engine::detail
