// The parent's side of the import workers (import_worker.hpp, worker_protocol.hpp).
//
// A worker is started with posix_spawn (glibc's is a vfork-like clone followed by exec: the
// caller's memory is never copied, so starting one from a large process or from a Python
// interpreter costs the same as from a small one, and no lock another thread holds is carried
// into it). Its two descriptors are placed at kWorkerSocket and kWorkerAnswer; every other
// descriptor of ours is close-on-exec, and the worker closes anything above them that is not.
// Requests carry the file's absolute path, so a worker serves its thread whatever the working
// directory has become since it started; messages name the file as the caller gave it.
#include "import_worker.hpp"

#include <dlfcn.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/mman.h>
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
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <system_error>
#include <utility>
#include <vector>

#include "base/errors.hpp"
#include "base/process.hpp"
#include "worker_protocol.hpp"

namespace tumble::engine::detail {
namespace {

constexpr std::uint64_t kMiB = std::uint64_t{1} << 20;
constexpr std::uint64_t kGiB = std::uint64_t{1} << 30;
/// CPU seconds under which a worker that missed its wall-clock deadline counts as stalled
/// (blocked, not reading) rather than slow.
constexpr double kStalledCpuSeconds = 1.0;

/// Answers of this thread still mapped (run_in_worker refuses a request while one is).
thread_local int live_answers = 0;

/// How a worker ended: its wait status, whether it was killed for exceeding the wall-clock
/// deadline, and the CPU time the file used (the limit's SIGKILL is told from the kernel's by
/// it).
struct WorkerEnd {
  int status = 0;
  bool timed_out = false;
  double cpu_seconds = 0.0;
};

WorkerEnd reap(pid_t child, bool timed_out) {
  WorkerEnd end;
  end.timed_out = timed_out;
  rusage usage{};
  while (::wait4(child, &end.status, 0, &usage) < 0 && errno == EINTR) {
  }
  end.cpu_seconds = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                    1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
  return end;
}

std::string format_seconds(double seconds) {
  std::array<char, 32> text{};
  std::snprintf(text.data(), text.size(), "%g s", seconds);
  return text.data();
}

std::string format_bytes(std::uint64_t bytes) {
  std::array<char, 32> text{};
  std::snprintf(text.data(), text.size(), "%.3g GiB", static_cast<double>(bytes) / kGiB);
  return text.data();
}

/// Why a worker that sent no answer ended, as the end of a sentence. A SIGKILL past the CPU
/// limit is the limit's (the hard limit), one before it someone else's (the kernel's
/// out-of-memory killer, a user).
std::string describe_end(const WorkerEnd& end, const ImportLimits& limits, const char* what) {
  const std::string reader = what;
  if (end.timed_out)
    return reader + " did not finish reading it in time (it may loop on this file)";
  if (WIFEXITED(end.status) && WEXITSTATUS(end.status) == kCannotAnswer) {
    return "the mesh " + reader + " read could not be passed back (no memory or file space left)";
  }
  if (WIFSIGNALED(end.status)) {
    const int signal = WTERMSIG(end.status);
    if (signal == SIGXCPU || (signal == SIGKILL && end.cpu_seconds >= limits.cpu_seconds)) {
      return reader + " used more than " + format_seconds(limits.cpu_seconds) +
             " of CPU time reading it (it may loop on this file)";
    }
    const char* abbreviation = sigabbrev_np(signal);
    const std::string signal_name = abbreviation != nullptr ? std::string("SIG") + abbreviation
                                                            : "signal " + std::to_string(signal);
    if (signal == SIGINT || signal == SIGTERM)
      return "reading it was interrupted (" + signal_name + ")";
    if (signal == SIGKILL) {
      return reader + " was killed (SIGKILL) reading it, perhaps by the kernel for want of memory";
    }
    const char* description = sigdescr_np(signal);
    return reader + " crashed reading it (" + signal_name + ", " +
           (description != nullptr ? description : "unknown signal") +
           "): the file is malformed in a way " + reader + " does not survive";
  }
  return reader + " ended without an answer (exit status " +
         std::to_string(WIFEXITED(end.status) ? WEXITSTATUS(end.status) : -1) + ")";
}

/// Waits for a reply on `socket` until `seconds` pass. Nothing when the worker ended (its end
/// of the socket closed) or the time passed (`timed_out`). Signals for the parent do not cut
/// the wait short.
std::optional<WorkerReply> wait_for_reply(int socket, double seconds, bool& timed_out) {
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double>(seconds));
  WorkerReply reply;
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

/// The whole memory file, mapped read-only (null for an empty file).
std::pair<const void*, std::size_t> map_answer(int fd) {
  struct stat status {};
  if (::fstat(fd, &status) != 0 || status.st_size <= 0) return {nullptr, 0};
  const auto size = static_cast<std::size_t>(status.st_size);
  void* mapping = ::mmap(nullptr, size, PROT_READ, MAP_SHARED, fd, 0);
  if (mapping == MAP_FAILED) throw std::bad_alloc();
  return {mapping, size};
}

/// The answer's text (an error's message); empty when it is cut short.
std::string answer_text(const std::byte* bytes, std::size_t size) {
  std::uint64_t length = 0;
  if (size < kAnswerHeader + sizeof length) return {};
  std::memcpy(&length, bytes + kAnswerHeader, sizeof length);
  if (length > size - kAnswerHeader - sizeof length) return {};
  return std::string(reinterpret_cast<const char*>(bytes + kAnswerHeader + sizeof length), length);
}

/// The worker's answer for a file it replied to: the mapped payload, or the refusal it says.
WorkerAnswer judge_answer(const std::filesystem::path& file, const ImportLimits& limits,
                          const char* what, int message) {
  const auto [mapping, size] = map_answer(message);
  WorkerAnswer answer(mapping, size, kAnswerHeader);
  const auto* bytes = static_cast<const std::byte*>(mapping);
  const auto tag = size >= kAnswerHeader ? static_cast<std::uint8_t>(bytes[0]) : std::uint8_t{0};
  if (tag == kAnswer) return answer;
  const std::string text = answer_text(bytes, size);
  if (tag == kInputError) throw InputError(text);
  const std::string name = file.string();
  if (tag == kOutOfMemory) {
    throw InputError(name + ": " + what + " needs more than " + format_bytes(limits.memory_bytes) +
                     " of memory to read it");
  }
  if (tag == kFailure) throw InputError(name + ": " + what + " failed reading it (" + text + ")");
  throw InputError(name + ": " + what + " sent an answer that cannot be read");
}

/// posix_spawn's file actions and attributes, destroyed with their owner.
struct SpawnSetup {
  posix_spawn_file_actions_t actions;
  posix_spawnattr_t attributes;

  SpawnSetup() {
    posix_spawn_file_actions_init(&actions);
    posix_spawnattr_init(&attributes);
  }
  ~SpawnSetup() {
    posix_spawnattr_destroy(&attributes);
    posix_spawn_file_actions_destroy(&actions);
  }
  SpawnSetup(const SpawnSetup&) = delete;
  SpawnSetup& operator=(const SpawnSetup&) = delete;
};

/// A descriptor, closed with its owner.
struct Descriptor {
  int fd = -1;
  explicit Descriptor(int value) : fd(value) {}
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  int release() { return std::exchange(fd, -1); }
};

/// Starts `program` as a worker holding `socket` and `answer` at their fixed numbers, with
/// stdin and stdout on /dev/null and every signal at its default action, unblocked. Returns
/// its process id, or -1 with errno set.
pid_t spawn_worker(const std::filesystem::path& program, int socket, int answer) {
  SpawnSetup setup;
  posix_spawn_file_actions_addopen(&setup.actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&setup.actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_adddup2(&setup.actions, socket, kWorkerSocket);
  posix_spawn_file_actions_adddup2(&setup.actions, answer, kWorkerAnswer);
  sigset_t all;
  sigset_t none;
  sigfillset(&all);
  sigemptyset(&none);
  posix_spawnattr_setsigdefault(&setup.attributes, &all);
  posix_spawnattr_setsigmask(&setup.attributes, &none);
  posix_spawnattr_setflags(&setup.attributes, POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETSIGMASK);
  const std::string parent = std::to_string(::getpid());
  const std::string path = program.string();
  std::array<char*, 4> argv{const_cast<char*>(path.c_str()), const_cast<char*>(kWorkerFlag),
                            const_cast<char*>(parent.c_str()), nullptr};
  // assimp's OBJ reader fills a 16 MiB line buffer for every file however small: 4,096 page
  // faults with 4 KiB pages, half the worker's CPU time on a 12-triangle cube; a few with
  // huge pages.
  std::vector<char*> environment = environment_with_huge_pages();
  pid_t child = -1;
  const int error = ::posix_spawn(&child, path.c_str(), &setup.actions, &setup.attributes,
                                  argv.data(), environment.data());
  if (error != 0) {
    errno = error;
    return -1;
  }
  return child;
}

/// The parent's handle on one thread's worker of one program.
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
  WorkerAnswer run(const std::filesystem::path& file, const ImportLimits& limits, const char* what,
                   const std::filesystem::path& program, const std::string& request, bool& retry);

 private:
  void start(const std::filesystem::path& file, const std::filesystem::path& program);
  /// Closes the parent's descriptors of a worker already reaped.
  void forget() {
    ::close(socket_);
    ::close(message_);
    pid_ = -1;
    socket_ = message_ = -1;
    files_ = 0;
    cpu_microseconds_ = 0;
  }
  /// Sends `request`, starting a fresh worker when there is none, it runs another program or
  /// it has ended since.
  void send(const std::filesystem::path& file, const std::filesystem::path& program,
            const std::string& request);
  WorkerAnswer judge_end(const std::filesystem::path& file, const ImportLimits& limits,
                         const char* what, bool timed_out, bool& retry);

  pid_t pid_ = -1;
  std::filesystem::path program_;
  int socket_ = -1;
  int message_ = -1;
  unsigned files_ = 0;
  std::uint64_t cpu_microseconds_ = 0;  // used by the worker before the current file
};

void Worker::start(const std::filesystem::path& file, const std::filesystem::path& program) {
  const auto cannot_start = [&](const char* call) {
    return std::system_error(errno, std::generic_category(),
                             "cannot start reading " + file.string() + " (" + call + ")");
  };
  // Above the worker's fixed numbers, so that placing them never meets one of them.
  Descriptor memory(::memfd_create("tumble-import-answer", MFD_CLOEXEC));
  if (memory.fd < 0) throw cannot_start("memfd_create");
  Descriptor message(::fcntl(memory.fd, F_DUPFD_CLOEXEC, kWorkerAnswer + 1));
  std::array<int, 2> pair{};
  if (message.fd < 0 || ::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, pair.data()) != 0) {
    throw cannot_start("socketpair");
  }
  Descriptor ours(pair[0]);
  Descriptor raw_theirs(pair[1]);
  Descriptor theirs(::fcntl(raw_theirs.fd, F_DUPFD_CLOEXEC, kWorkerAnswer + 1));
  if (theirs.fd < 0) throw cannot_start("fcntl");
  const pid_t child = spawn_worker(program, theirs.fd, message.fd);
  if (child < 0) throw cannot_start(("posix_spawn " + program.string()).c_str());
  pid_ = child;
  program_ = program;
  socket_ = ours.release();
  message_ = message.release();
}

void Worker::send(const std::filesystem::path& file, const std::filesystem::path& program,
                  const std::string& request) {
  for (int attempt = 0; attempt < 2; ++attempt) {
    if (pid_ > 0 && program_ != program) stop();
    if (pid_ <= 0) start(file, program);
    if (::ftruncate(message_, 0) != 0) {  // (cannot fail on a memfd of one's own)
      stop();
      continue;
    }
    if (send_all(socket_, request.data(), request.size())) return;
    stop();  // it ended between two files (killed from outside): no file's fault
  }
  throw std::system_error(errno, std::generic_category(),
                          "cannot start reading " + file.string() + " (import worker)");
}

WorkerAnswer Worker::run(const std::filesystem::path& file, const ImportLimits& limits,
                         const char* what, const std::filesystem::path& program,
                         const std::string& request, bool& retry) {
  retry = false;
  send(file, program, request);
  bool timed_out = false;
  const std::optional<WorkerReply> reply =
      wait_for_reply(socket_, 2.0 * limits.cpu_seconds + 10.0, timed_out);
  if (!reply) return judge_end(file, limits, what, timed_out, retry);
  cpu_microseconds_ = reply->cpu_microseconds;
  // A refusal (assimp's own "cannot read", or a check of its scene) leaves the worker as it
  // was: assimp unwinds its readers' errors by exceptions, and what it leaks counts towards
  // kWorkerGrowth. After an allocation failure or an unexpected exception its heap may be in
  // any state: replaced. (Most files a fuzzer or a batch of odd files gives are refusals;
  // a fresh worker costs a program start.)
  const bool clean = reply->tag == kAnswer || reply->tag == kInputError;
  const bool recycle = !clean || ++files_ >= kWorkerFiles || reply->growth > kWorkerGrowth;
  // The answer stays mapped after the worker ends (the mapping holds the memory file).
  struct StopAfter {
    Worker& worker;
    bool stop;
    ~StopAfter() {
      if (stop) worker.stop();
    }
  } stop_after{*this, recycle};
  return judge_answer(file, limits, what, message_);
}

/// A worker that ended (or is ended now) without replying: judged on how it ended and the CPU
/// time this file used.
WorkerAnswer Worker::judge_end(const std::filesystem::path& file, const ImportLimits& limits,
                               const char* what, bool timed_out, bool& retry) {
  if (timed_out) ::kill(pid_, SIGKILL);
  WorkerEnd end = reap(pid_, timed_out);
  end.cpu_seconds = std::max(0.0, end.cpu_seconds - 1e-6 * static_cast<double>(cpu_microseconds_));
  // A crash, a kill or a lost answer may be an earlier file's doing; a limit or an
  // interruption is not. A worker that sat out the whole wall-clock deadline on next to no CPU
  // time was not reading (a looping reader meets its CPU limit first): it was blocked, which
  // is not the file's doing either.
  const int signal = WIFSIGNALED(end.status) ? WTERMSIG(end.status) : 0;
  const bool stalled = timed_out && end.cpu_seconds < kStalledCpuSeconds;
  retry = stalled ||
          (files_ > 0 && !timed_out && signal != SIGXCPU && signal != SIGINT && signal != SIGTERM);
  forget();
  throw InputError(file.string() + ": " + describe_end(end, limits, what));
}

thread_local Worker this_threads_worker;

/// The request's bytes (worker_protocol.hpp).
std::string request_bytes(const std::string& task, const ImportLimits& limits,
                          const std::vector<std::string>& request) {
  std::string bytes;
  append_text(bytes, task);
  append_bytes(bytes, limits.cpu_seconds);
  append_bytes(bytes, limits.memory_bytes);
  append_bytes(bytes, std::uint64_t{request.size()});
  for (const std::string& text : request) append_text(bytes, text);
  return bytes;
}

/// True when `path` names a file this process may execute.
bool executable(const std::filesystem::path& path) {
  return !path.empty() && ::access(path.c_str(), X_OK) == 0 &&
         std::filesystem::is_regular_file(path);
}

}  // namespace

WorkerAnswer::WorkerAnswer(const void* mapping, std::size_t mapped, std::size_t payload_offset)
    : mapping_(mapping), mapped_(mapped), offset_(std::min(payload_offset, mapped)) {
  if (mapping_ != nullptr) ++live_answers;
}

WorkerAnswer::WorkerAnswer(WorkerAnswer&& other) noexcept
    : mapping_(std::exchange(other.mapping_, nullptr)),
      mapped_(std::exchange(other.mapped_, 0)),
      offset_(std::exchange(other.offset_, 0)) {}

WorkerAnswer::~WorkerAnswer() {
  if (mapping_ == nullptr) return;
  ::munmap(const_cast<void*>(mapping_), mapped_);
  --live_answers;
}

std::span<const std::byte> WorkerAnswer::payload() const {
  if (mapping_ == nullptr) return {};
  return {static_cast<const std::byte*>(mapping_) + offset_, mapped_ - offset_};
}

ImportLimits effective_limits(const ImportLimits& requested, std::uintmax_t size) {
  ImportLimits limits = requested;
  const double mib = static_cast<double>(size) / static_cast<double>(kMiB);
  if (!(limits.cpu_seconds > 0.0)) limits.cpu_seconds = 10.0 + 2.0 * std::floor(mib);
  if (limits.memory_bytes == 0) {
    const auto physical = static_cast<std::uint64_t>(::sysconf(_SC_PHYS_PAGES)) *
                          static_cast<std::uint64_t>(::sysconf(_SC_PAGESIZE));
    limits.memory_bytes = std::min<std::uint64_t>(2 * kGiB + 64 * std::uint64_t{size},
                                                  std::max<std::uint64_t>(physical, kGiB));
  }
  return limits;
}

std::filesystem::path import_worker_program() {
  static const std::filesystem::path found = [] {
    std::vector<std::filesystem::path> places;
    if (const char* given = std::getenv("TUMBLE_IMPORT_WORKER"); given != nullptr && *given) {
      places.emplace_back(given);
    }
    Dl_info info{};
    if (::dladdr(reinterpret_cast<void*>(&import_worker_program), &info) != 0 &&
        info.dli_fname != nullptr && info.dli_fname[0] == '/') {
      places.push_back(std::filesystem::path(info.dli_fname).parent_path() / "tumble-import");
    }
    std::error_code error;
    const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
    if (!error) places.push_back(self.parent_path() / "tumble-import");
    places.emplace_back(TUMBLE_IMPORT_WORKER_BUILT);
    places.emplace_back(TUMBLE_IMPORT_WORKER_INSTALLED);
    for (const std::filesystem::path& place : places) {
      if (executable(place)) return place;
    }
    std::string list;
    for (const std::filesystem::path& place : places)
      list += (list.empty() ? "" : ", ") + place.string();
    throw std::runtime_error("the import worker tumble-import was not found (looked for " + list +
                             ")");
  }();
  return found;
}

WorkerAnswer run_in_worker(const std::filesystem::path& file, const ImportLimits& limits,
                           const char* what, const std::filesystem::path& program,
                           const std::string& task, const std::vector<std::string>& request) {
  if (live_answers > 0) {
    throw std::logic_error("run_in_worker: an earlier answer of this thread is still in use");
  }
  const std::string bytes = request_bytes(task, limits, request);
  bool retry = false;
  try {
    return this_threads_worker.run(file, limits, what, program, bytes, retry);
  } catch (const InputError&) {
    if (!retry) throw;
  }
  return this_threads_worker.run(file, limits, what, program, bytes, retry);
}

std::optional<pid_t> import_worker_pid() {
  return this_threads_worker.pid();
}

void stop_import_worker() {
  this_threads_worker.stop();
}

}  // namespace tumble::engine::detail
