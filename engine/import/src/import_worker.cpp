// The import workers (import_worker.hpp).
//
// A worker is forked (under the fork lock of isolated_import.cpp) with two descriptors of its
// own: its end of a socket pair, on which it reads requests and sends replies, and a memory
// file (memfd) into which it writes each answer in run_isolated's format. It closes every other
// descriptor it inherited (another thread's pipes or sockets would otherwise stay open as long
// as it lives), dies with the thread that forked it (PR_SET_PDEATHSIG) and ends on the end of
// its socket. Messages on the socket:
//   request: u64 task (the function's address), f64 CPU seconds, u64 memory bytes, u64 count
//            of strings, then each as u64 length + bytes
//   reply:   u64 tag of the answer, u64 CPU time used so far (microseconds), u64 growth of the
//            resident memory since the worker started (bytes)
// Before each file the worker sets the soft RLIMIT_CPU to the CPU time it has used + the file's
// budget (rounded up to whole seconds, as the limit is), and the soft RLIMIT_AS to its address
// space now + the file's memory budget; the hard limits stay as inherited, since a process
// cannot raise a hard limit again for the next file. SIGXCPU's default action ends the worker
// at the soft limit; the parent's wall-clock deadline is the backstop.
#include "import_worker.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <fstream>
#include <system_error>
#include <utility>

#include "base/errors.hpp"
#include "isolated_import.hpp"

namespace tumble::engine::detail {
namespace {

constexpr std::size_t kMaxRequest = std::size_t{1} << 20;
/// CPU seconds under which a worker that missed its wall-clock deadline counts as stalled
/// (blocked, not reading) rather than slow.
constexpr double kStalledCpuSeconds = 1.0;

/// Exact reads and writes on a socket; false when the other end is gone.
bool send_all(int fd, const void* data, std::size_t size) {
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

template <typename T>
void append(std::string& out, const T& value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof value);
}

struct Reply {
  std::uint64_t tag = 0;
  std::uint64_t cpu_microseconds = 0;
  std::uint64_t growth = 0;
};

std::uint64_t cpu_microseconds_used() {
  rusage usage{};
  ::getrusage(RUSAGE_SELF, &usage);
  return static_cast<std::uint64_t>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) * 1000000 +
         static_cast<std::uint64_t>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

std::uint64_t resident_bytes() {
  std::ifstream statm("/proc/self/statm");
  std::uint64_t pages = 0;
  std::uint64_t resident = 0;
  statm >> pages >> resident;
  return resident * static_cast<std::uint64_t>(::sysconf(_SC_PAGESIZE));
}

/// The worker's limits for the next file: its budgets on top of what it has used so far.
void set_file_limits(double cpu_seconds, std::uint64_t memory_bytes) {
  rlimit cpu{};
  ::getrlimit(RLIMIT_CPU, &cpu);
  const double used = 1e-6 * static_cast<double>(cpu_microseconds_used());
  cpu.rlim_cur = std::min(static_cast<rlim_t>(std::ceil(used + cpu_seconds)), cpu.rlim_max);
  ::setrlimit(RLIMIT_CPU, &cpu);
#ifndef TUMBLE_ADDRESS_SANITIZER
  rlimit memory{};
  ::getrlimit(RLIMIT_AS, &memory);
  memory.rlim_cur = std::min<rlim_t>(current_address_space() + memory_bytes, memory.rlim_max);
  ::setrlimit(RLIMIT_AS, &memory);
#else
  (void)memory_bytes;
#endif
}

void lift_memory_limit() {
#ifndef TUMBLE_ADDRESS_SANITIZER
  rlimit memory{};
  ::getrlimit(RLIMIT_AS, &memory);
  memory.rlim_cur = memory.rlim_max;
  ::setrlimit(RLIMIT_AS, &memory);
#endif
}

/// Closes every descriptor above stderr but `keep`.
void close_all_but(std::array<int, 2> keep) {
  std::sort(keep.begin(), keep.end());
  unsigned first = 3;
  for (const int fd : keep) {
    if (static_cast<unsigned>(fd) > first) ::close_range(first, static_cast<unsigned>(fd) - 1, 0);
    first = static_cast<unsigned>(fd) + 1;
  }
  ::close_range(first, ~0U, 0);
}

/// Reads one request; false at the end of the socket (or a malformed request).
bool read_request(int socket, WorkerTask& task, double& cpu_seconds, std::uint64_t& memory,
                  std::vector<std::string>& strings) {
  std::uint64_t count = 0;
  if (!receive_all(socket, &task, sizeof task) ||
      !receive_all(socket, &cpu_seconds, sizeof cpu_seconds) ||
      !receive_all(socket, &memory, sizeof memory) || !receive_all(socket, &count, sizeof count) ||
      count > kMaxRequest) {
    return false;
  }
  strings.assign(count, std::string());
  for (std::string& text : strings) {
    std::uint64_t size = 0;
    if (!receive_all(socket, &size, sizeof size) || size > kMaxRequest) return false;
    text.resize(size);
    if (!receive_all(socket, text.data(), size)) return false;
  }
  return true;
}

[[noreturn]] void worker_main(int socket, int message, pid_t parent) {
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) ::_exit(4);  // the parent died before the line above
  reset_child_signals();
  close_all_but({socket, message});
  const std::uint64_t start_resident = resident_bytes();
  WorkerTask task = nullptr;
  double cpu_seconds = 0.0;
  std::uint64_t memory = 0;
  std::vector<std::string> strings;
  while (read_request(socket, task, cpu_seconds, memory, strings)) {
    set_file_limits(cpu_seconds, memory);
    Reply reply;
    reply.tag = answer(message, [&](ImportStats& stats) { return task(strings, stats); });
    lift_memory_limit();  // the reply needs a little memory, even after a bad_alloc
    reply.cpu_microseconds = cpu_microseconds_used();
    const std::uint64_t resident = resident_bytes();
    reply.growth = resident > start_resident ? resident - start_resident : 0;
    if (!send_all(socket, &reply, sizeof reply)) break;
  }
  ::_exit(0);
}

/// The calling process's working directory as (device, inode); zeros when it cannot be examined.
std::pair<dev_t, ino_t> working_directory() {
  struct stat status {};
  if (::stat(".", &status) != 0) return {};
  return {status.st_dev, status.st_ino};
}

/// Waits for a reply on `socket` until `seconds` pass. Nothing when the worker ended (its end
/// of the socket closed) or the time passed (`timed_out`). Signals for the parent do not cut
/// the wait short.
std::optional<Reply> wait_for_reply(int socket, double seconds, bool& timed_out) {
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double>(seconds));
  Reply reply;
  auto* p = reinterpret_cast<char*>(&reply);
  std::size_t got = 0;
  timed_out = false;
  while (got < sizeof reply) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return timed_out = true, std::nullopt;
    pollfd poll_fd{socket, POLLIN, 0};
    const int ready =
        ::poll(&poll_fd, 1, static_cast<int>(std::min<long long>(left.count(), 1LL << 30)));
    if (ready < 0 && errno != EINTR) return std::nullopt;  // cannot wait: treat as ended
    if (ready <= 0) continue;
    const ssize_t n = ::recv(socket, p + got, sizeof reply - got, MSG_DONTWAIT);
    if (n == 0 || (n < 0 && errno != EINTR && errno != EAGAIN)) return std::nullopt;
    if (n > 0) got += static_cast<std::size_t>(n);
  }
  return reply;
}

/// The parent's handle on one thread's worker.
class Worker {
 public:
  Worker() = default;
  Worker(const Worker&) = delete;
  Worker& operator=(const Worker&) = delete;
  ~Worker() { stop(); }

  [[nodiscard]] std::optional<pid_t> pid() const {
    return pid_ > 0 ? std::optional<pid_t>(pid_) : std::nullopt;
  }

  /// Kills and reaps the worker, if there is one.
  void stop() {
    if (pid_ <= 0) return;
    ::kill(pid_, SIGKILL);
    reap(pid_, false);
    forget();
  }

  /// One file, in this worker (started if need be). `retry` is set when the worker died on
  /// it after reading other files: the caller then tries once more in a fresh one.
  TriangleMesh run(const std::filesystem::path& file, const ImportLimits& limits, const char* what,
                   ImportStats& stats, const std::string& request, bool& retry);

 private:
  void start(const std::filesystem::path& file);
  /// Closes the parent's descriptors of a worker already reaped.
  void forget() {
    ::close(socket_);
    ::close(message_);
    pid_ = -1;
    socket_ = message_ = -1;
    files_ = 0;
    cpu_microseconds_ = 0;
  }
  /// Sends `request`, starting a fresh worker when there is none or it has ended since.
  void send(const std::filesystem::path& file, const std::string& request);

  pid_t pid_ = -1;
  /// The parent's working directory (device, inode) when the worker was forked: the worker
  /// resolves the relative paths of requests against it, so it serves no file once the
  /// parent's has changed.
  std::pair<dev_t, ino_t> directory_{};
  int socket_ = -1;
  int message_ = -1;
  unsigned files_ = 0;
  std::uint64_t cpu_microseconds_ = 0;  // used by the worker before the current file
};

void Worker::start(const std::filesystem::path& file) {
  const auto cannot_start = [&](const char* call) {
    return std::system_error(errno, std::generic_category(),
                             "cannot start reading " + file.string() + " (" + call + ")");
  };
  std::unique_lock fork_lock(import_fork_mutex());
  const int message = ::memfd_create("tumble-import-worker", MFD_CLOEXEC);
  if (message < 0) throw cannot_start("memfd_create");
  std::array<int, 2> sockets{};
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sockets.data()) != 0) {
    const auto error = cannot_start("socketpair");
    ::close(message);
    throw error;
  }
  const std::pair<dev_t, ino_t> directory = working_directory();
  const pid_t parent = ::getpid();
  const pid_t child = ::fork();
  if (child < 0) {
    const auto error = cannot_start("fork");
    for (const int fd : {message, sockets[0], sockets[1]}) ::close(fd);
    throw error;
  }
  if (child == 0) {
    ::close(sockets[0]);
    worker_main(sockets[1], message, parent);
  }
  ::close(sockets[1]);
  directory_ = directory;
  pid_ = child;
  socket_ = sockets[0];
  message_ = message;
}

void Worker::send(const std::filesystem::path& file, const std::string& request) {
  for (int attempt = 0; attempt < 2; ++attempt) {
    if (pid_ > 0 && working_directory() != directory_) stop();
    if (pid_ <= 0) start(file);
    if (::ftruncate(message_, 0) != 0) {  // (cannot fail on a memfd of one's own)
      stop();
      continue;
    }
    ::lseek(message_, 0, SEEK_SET);
    if (send_all(socket_, request.data(), request.size())) return;
    stop();  // it ended between two files (killed from outside): no file's fault
  }
  throw std::system_error(errno, std::generic_category(),
                          "cannot start reading " + file.string() + " (import worker)");
}

TriangleMesh Worker::run(const std::filesystem::path& file, const ImportLimits& limits,
                         const char* what, ImportStats& stats, const std::string& request,
                         bool& retry) {
  retry = false;
  send(file, request);
  bool timed_out = false;
  const std::optional<Reply> reply =
      wait_for_reply(socket_, 2.0 * limits.cpu_seconds + 10.0, timed_out);
  if (reply) {
    cpu_microseconds_ = reply->cpu_microseconds;
    // A file it did not read cleanly may have left assimp's heap in any state: replaced.
    const bool clean = reply->tag == kMesh;
    const bool recycle = !clean || ++files_ >= kWorkerFiles || reply->growth > kWorkerGrowth;
    struct StopAfter {
      Worker& worker;
      bool stop;
      ~StopAfter() {
        if (stop) worker.stop();
      }
    } stop_after{*this, recycle};
    return judge_answer(file, limits, what, stats, message_, std::nullopt);
  }
  // It ended (or is ended now) without replying: judged as run_isolated judges its child,
  // on the CPU time this file used.
  if (timed_out) ::kill(pid_, SIGKILL);
  ChildEnd end = reap(pid_, timed_out);
  end.cpu_seconds = std::max(0.0, end.cpu_seconds - 1e-6 * static_cast<double>(cpu_microseconds_));
  // A crash, a kill or a lost answer may be an earlier file's doing; a limit or an
  // interruption is not.
  const int signal = WIFSIGNALED(end.status) ? WTERMSIG(end.status) : 0;
  // A worker that sat out the whole wall-clock deadline on next to no CPU time was not reading
  // (a looping reader meets its CPU limit first): it was blocked. Under AddressSanitizer a
  // worker forked while another thread held one of the runtime's locks waits on it for ever
  // (GCC 12's libasan does not reset them in the child; glibc resets malloc's). Not the
  // file's doing either: once more in a fresh worker.
  const bool stalled = timed_out && end.cpu_seconds < kStalledCpuSeconds;
  retry = stalled ||
          (files_ > 0 && !timed_out && signal != SIGXCPU && signal != SIGINT && signal != SIGTERM);
  try {
    TriangleMesh mesh = judge_answer(file, limits, what, stats, message_, end);
    forget();
    retry = false;
    return mesh;
  } catch (...) {
    forget();
    throw;
  }
}

thread_local Worker this_threads_worker;

}  // namespace

TriangleMesh run_in_worker(const std::filesystem::path& file, const ImportLimits& limits,
                           const char* what, ImportStats& stats, WorkerTask task,
                           const std::vector<std::string>& request) {
  std::string bytes;
  append(bytes, task);
  append(bytes, limits.cpu_seconds);
  append(bytes, limits.memory_bytes);
  append(bytes, std::uint64_t{request.size()});
  for (const std::string& text : request) {
    append(bytes, std::uint64_t{text.size()});
    bytes += text;
  }
  bool retry = false;
  try {
    return this_threads_worker.run(file, limits, what, stats, bytes, retry);
  } catch (const InputError&) {
    if (!retry) throw;
  }
  stats = ImportStats{};
  return this_threads_worker.run(file, limits, what, stats, bytes, retry);
}

std::optional<pid_t> import_worker_pid() {
  return this_threads_worker.pid();
}

void stop_import_worker() {
  this_threads_worker.stop();
}

}  // namespace tumble::engine::detail
