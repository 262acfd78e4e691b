#pragma once
// What the import worker (a program of its own, tumble-import) and the process that starts it
// say to each other. Shared by both sides: the parent (import_worker.cpp) and the worker's loop
// (worker_serve.cpp).
//
// The parent starts the worker with posix_spawn (a fresh program: nothing of the parent's
// memory, threads or interpreter is copied) and hands it two descriptors at fixed numbers:
//   kWorkerSocket  its end of a socket pair: requests in, replies out;
//   kWorkerAnswer  an anonymous memory file (memfd) into which it writes each answer.
// Messages on the socket (native byte order: both ends are one machine):
//   request: text task, f64 CPU seconds, u64 memory bytes, u64 count, then count texts
//            (a text is a u64 length and its bytes)
//   reply:   u64 tag of the answer, u64 CPU time used so far (microseconds), u64 growth of the
//            resident memory since the worker started (bytes)
// The answer in the memory file: one byte, the tag, seven bytes of padding (so the payload is
// 8-byte aligned in a mapping of the file), then the payload: for kAnswer the task's bytes,
// for the others one text.

#include <sys/socket.h>
#include <sys/types.h>

#include <cerrno>
#include <cstddef>
#include <cstdint>
#include <string>

namespace tumble::engine::detail {

/// The worker's descriptors, as the parent places them.
inline constexpr int kWorkerSocket = 3;
inline constexpr int kWorkerAnswer = 4;

/// The first argument of a worker started by a parent; the second is the parent's process id
/// (the worker ends at once when its parent is no longer that process).
inline constexpr const char* kWorkerFlag = "--serve-import-requests";

/// What an answer's first byte says it holds.
enum AnswerTag : std::uint8_t { kAnswer = 1, kInputError = 2, kOutOfMemory = 3, kFailure = 4 };

/// Bytes before an answer's payload.
inline constexpr std::size_t kAnswerHeader = 8;

/// A worker's exit status when it cannot write its answer (no memory left for the file, or a
/// file size limit).
inline constexpr int kCannotAnswer = 3;

/// A worker's reply on the socket once its answer is written.
struct WorkerReply {
  std::uint64_t tag = 0;
  std::uint64_t cpu_microseconds = 0;
  std::uint64_t growth = 0;
};

/// Longest text a request may hold (a path, a task name).
inline constexpr std::uint64_t kMaxRequestText = std::uint64_t{1} << 20;

/// Appends `value`'s bytes to `out`.
template <typename T>
void append_bytes(std::string& out, const T& value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof value);
}

/// Appends a text (u64 length, bytes) to `out`.
inline void append_text(std::string& out, const std::string& text) {
  append_bytes(out, std::uint64_t{text.size()});
  out += text;
}

/// Sends all `size` bytes at `data` on the socket `fd` (again after a signal, never raising
/// SIGPIPE); false when the peer is gone or the socket fails.
inline bool send_all(int fd, const void* data, std::size_t size) {
  const auto* p = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = ::send(fd, p, size, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    p += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

}  // namespace tumble::engine::detail
