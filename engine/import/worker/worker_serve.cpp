// The import worker's loop (worker_serve.hpp, worker_protocol.hpp).
//
// Before each file the worker sets the soft RLIMIT_CPU to the CPU time it has used + the file's
// budget (rounded up to whole seconds, as the limit is), and the soft RLIMIT_AS to its address
// space now + the file's memory budget; the hard limits stay as inherited, since a process
// cannot raise a hard limit again for the next file. SIGXCPU's default action ends the worker
// at the soft limit; the parent's wall-clock deadline is the backstop. The worker leaves by
// _exit, so no exit-time work (the leak checker's scan of assimp's leaks) runs in it.
#include "worker_serve.hpp"

#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <new>

#include "base/errors.hpp"
#include "worker_protocol.hpp"

namespace tumble::engine::detail {
namespace {

/// Writes smaller than this go through the buffer.
constexpr std::size_t kAnswerBuffer = std::size_t{1} << 16;

bool receive_all(int fd, void* data, std::size_t size) {
  auto* p = static_cast<char*>(data);
  while (size > 0) {
    const ssize_t n = ::recv(fd, p, size, 0);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    p += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

bool receive_text(int fd, std::string& text) {
  std::uint64_t size = 0;
  if (!receive_all(fd, &size, sizeof size) || size > kMaxRequestText) return false;
  text.resize(size);
  return receive_all(fd, text.data(), size);
}

/// Writes all of `data` at the descriptor's offset, or ends the worker.
void write_or_end(int fd, const void* data, std::size_t size) {
  const auto* p = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = ::write(fd, p, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) ::_exit(kCannotAnswer);
    p += n;
    size -= static_cast<std::size_t>(n);
  }
}

std::uint64_t cpu_microseconds_used() {
  rusage usage{};
  ::getrusage(RUSAGE_SELF, &usage);
  return static_cast<std::uint64_t>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) * 1000000 +
         static_cast<std::uint64_t>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

/// Pages of the address space and resident set (/proc/self/statm), in bytes.
std::pair<std::uint64_t, std::uint64_t> memory_now() {
  std::ifstream statm("/proc/self/statm");
  std::uint64_t pages = 0;
  std::uint64_t resident = 0;
  statm >> pages >> resident;
  const auto page = static_cast<std::uint64_t>(::sysconf(_SC_PAGESIZE));
  return {pages * page, resident * page};
}

// AddressSanitizer reserves terabytes of address space for its shadow: no memory limit there.
#if defined(__SANITIZE_ADDRESS__)
#define TUMBLE_WORKER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define TUMBLE_WORKER_ASAN 1
#endif
#endif

/// The worker's limits for the next file: its budgets on top of what it has used so far.
void set_file_limits(double cpu_seconds, std::uint64_t memory_bytes) {
  rlimit cpu{};
  ::getrlimit(RLIMIT_CPU, &cpu);
  const double used = 1e-6 * static_cast<double>(cpu_microseconds_used());
  cpu.rlim_cur = std::min(static_cast<rlim_t>(std::ceil(used + cpu_seconds)), cpu.rlim_max);
  ::setrlimit(RLIMIT_CPU, &cpu);
#ifndef TUMBLE_WORKER_ASAN
  rlimit memory{};
  ::getrlimit(RLIMIT_AS, &memory);
  memory.rlim_cur = std::min<rlim_t>(memory_now().first + memory_bytes, memory.rlim_max);
  ::setrlimit(RLIMIT_AS, &memory);
#else
  (void)memory_bytes;
#endif
}

void lift_memory_limit() {
#ifndef TUMBLE_WORKER_ASAN
  rlimit memory{};
  ::getrlimit(RLIMIT_AS, &memory);
  memory.rlim_cur = memory.rlim_max;
  ::setrlimit(RLIMIT_AS, &memory);
#endif
}

/// One request from the socket; false at its end (or on a malformed request).
struct Request {
  std::string task;
  double cpu_seconds = 0.0;
  std::uint64_t memory = 0;
  std::vector<std::string> texts;

  bool read(int socket) {
    std::uint64_t count = 0;
    if (!receive_text(socket, task) || !receive_all(socket, &cpu_seconds, sizeof cpu_seconds) ||
        !receive_all(socket, &memory, sizeof memory) ||
        !receive_all(socket, &count, sizeof count) || count > kMaxRequestText) {
      return false;
    }
    texts.assign(count, std::string());
    return std::all_of(texts.begin(), texts.end(),
                       [socket](std::string& text) { return receive_text(socket, text); });
  }
};

/// Starts the answer file afresh with `tag` and, for an error, its text.
void write_error(std::uint8_t tag, const std::string& text) {
  if (::ftruncate(kWorkerAnswer, 0) != 0 || ::lseek(kWorkerAnswer, 0, SEEK_SET) != 0) {
    ::_exit(kCannotAnswer);
  }
  AnswerWriter out(kWorkerAnswer);
  const std::uint64_t header = tag;  // the tag, then zero padding
  out.value(header);
  out.text(text);
  out.flush();
}

/// Runs `task` on the request and writes the whole answer; returns its tag.
std::uint8_t answer_request(WorkerTask task, const Request& request) {
  try {
    if (task == nullptr) throw std::runtime_error("no task named '" + request.task + "'");
    // The parent emptied the file; the offset is still where the last answer ended.
    if (::lseek(kWorkerAnswer, 0, SEEK_SET) != 0) ::_exit(kCannotAnswer);
    AnswerWriter out(kWorkerAnswer);
    const std::uint64_t placeholder = 0;
    out.value(placeholder);
    task(request.texts, out);
    out.flush();
    const std::uint8_t tag = kAnswer;
    if (::pwrite(kWorkerAnswer, &tag, 1, 0) != 1) ::_exit(kCannotAnswer);
    return kAnswer;
  } catch (const InputError& error) {
    write_error(kInputError, error.what());
    return kInputError;
  } catch (const std::bad_alloc&) {
    lift_memory_limit();  // the error's few bytes need memory too
    write_error(kOutOfMemory, "");
    return kOutOfMemory;
  } catch (const std::exception& error) {
    write_error(kFailure, error.what());
  } catch (...) {
    write_error(kFailure, "an unknown exception");
  }
  return kFailure;
}

/// What a fresh worker does before its first request.
void prepare_worker(pid_t parent) {
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) ::_exit(4);  // the parent died before the line above
  const rlimit no_core{0, 0};
  ::setrlimit(RLIMIT_CORE, &no_core);
  // Ctrl+C reaches the whole process group: the worker then simply ends, and the parent, which
  // saw the signal too, reports the interruption. A crash ends the worker by its signal, which
  // the parent names. posix_spawn reset the handlers the parent had; SIGXFSZ stays ignored when
  // the parent ignored it (a write past a file size limit then fails instead).
  for (const int signal : {SIGINT, SIGTERM, SIGPIPE, SIGXCPU, SIGSEGV, SIGBUS, SIGFPE, SIGILL}) {
    std::signal(signal, SIG_DFL);
  }
  ::close_range(kWorkerAnswer + 1, ~0U, 0);
}

}  // namespace

AnswerWriter::AnswerWriter(int fd) : fd_(fd) {
  buffer_.reserve(kAnswerBuffer);
}

void AnswerWriter::bytes(const void* data, std::size_t size) {
  offset_ += size;
  if (buffer_.size() + size <= kAnswerBuffer) {
    buffer_.append(static_cast<const char*>(data), size);
    return;
  }
  flush();
  write_or_end(fd_, data, size);
}

void AnswerWriter::text(std::string_view item) {
  value(std::uint64_t{item.size()});
  bytes(item.data(), item.size());
}

void AnswerWriter::align(std::size_t alignment) {
  static constexpr char kZeros[16] = {};
  const std::size_t pad = (alignment - offset_ % alignment) % alignment;
  bytes(kZeros, pad);
}

void AnswerWriter::flush() {
  write_or_end(fd_, buffer_.data(), buffer_.size());
  buffer_.clear();
}

bool started_as_worker(int argc, char** argv) {
  return argc == 3 && std::string_view(argv[1]) == kWorkerFlag;
}

int serve_import_requests(int argc, char** argv, std::span<const WorkerTaskEntry> tasks) {
  if (!started_as_worker(argc, argv)) return 2;
  prepare_worker(static_cast<pid_t>(std::strtol(argv[2], nullptr, 10)));
  const std::uint64_t start_resident = memory_now().second;
  Request request;
  while (request.read(kWorkerSocket)) {
    const auto entry = std::find_if(tasks.begin(), tasks.end(), [&](const WorkerTaskEntry& e) {
      return e.name == request.task;
    });
    set_file_limits(request.cpu_seconds, request.memory);
    WorkerReply reply;
    reply.tag = answer_request(entry == tasks.end() ? nullptr : entry->task, request);
    lift_memory_limit();  // the reply needs a little memory, even after a bad_alloc
    reply.cpu_microseconds = cpu_microseconds_used();
    const std::uint64_t resident = memory_now().second;
    reply.growth = resident > start_resident ? resident - start_resident : 0;
    if (!send_all(kWorkerSocket, &reply, sizeof reply)) break;
  }
  ::_exit(0);
}

}  // namespace tumble::engine::detail
