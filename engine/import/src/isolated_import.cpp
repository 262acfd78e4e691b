// The import in a child process (isolated_import.hpp).
//
// The child is a fork of tumble, not a new program: it needs no executable to find and runs the
// same code an in-process import would. It sets its own limits (RLIMIT_CPU, RLIMIT_AS, no core
// file), dies with its parent (PR_SET_PDEATHSIG), and writes one message into an anonymous
// memory file (memfd) the parent made before the fork:
//   u8 tag (kMesh, kInputError, kOutOfMemory, kFailure), then for kMesh the ImportStats
//   (three u64, two u8, the warnings as u64 count + length-prefixed strings), the positions
//   (u64 count + raw doubles) and the triangles (u64 count + raw u32 triples); for the others
//   one length-prefixed message.
// It leaves by _exit, so nothing of the parent's (stdio buffers, atexit handlers, the leak
// checker's exit-time scan) runs twice. The parent waits for the end of a pipe the child holds
// open (it closes when the child ends, however it ends), with a wall-clock deadline as a
// backstop for a child that blocks without using CPU time; then it reaps the child and reads
// the message. Through a memory file, a large mesh costs two memory copies; through the pipe
// itself it cost a context switch per 64 KiB as well.
#include "isolated_import.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <fstream>
#include <mutex>
#include <new>
#include <optional>
#include <string>
#include <system_error>

#include "base/errors.hpp"

namespace tumble::engine::detail {
namespace {

constexpr std::uint64_t kMiB = std::uint64_t{1} << 20;
constexpr std::uint64_t kGiB = std::uint64_t{1} << 30;

/// Everything the child writes goes through here; a failed write (no memory left) ends it.
struct PipeWriter {
  int fd;

  void bytes(const void* data, std::size_t size) const {
    const auto* p = static_cast<const char*>(data);
    while (size > 0) {
      const ssize_t n = ::write(fd, p, size);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) ::_exit(kCannotAnswer);
      p += n;
      size -= static_cast<std::size_t>(n);
    }
  }
  void u64(std::uint64_t value) const { bytes(&value, sizeof value); }
  void u8(std::uint8_t value) const { bytes(&value, sizeof value); }
  void text(const std::string& value) const {
    u64(value.size());
    bytes(value.data(), value.size());
  }
};

/// The parent's side: exact reads of the finished message. Any shortfall (the child ended
/// part-way) sets `short_read` and makes every later read fail too.
struct MessageReader {
  int fd;
  bool short_read = false;

  bool bytes(void* data, std::size_t size) {
    auto* p = static_cast<char*>(data);
    while (size > 0 && !short_read) {
      const ssize_t n = ::read(fd, p, size);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        short_read = true;
        break;
      }
      p += n;
      size -= static_cast<std::size_t>(n);
    }
    return !short_read;
  }
  std::uint64_t u64() {
    std::uint64_t value = 0;
    bytes(&value, sizeof value);
    return value;
  }
  std::uint8_t u8() {
    std::uint8_t value = 0;
    bytes(&value, sizeof value);
    return value;
  }
  std::string text() {
    const std::uint64_t size = u64();
    if (short_read || size > kGiB) return short_read = true, std::string();
    std::string value(size, '\0');
    bytes(value.data(), size);
    return value;
  }
};

void send_mesh(const PipeWriter& out, const TriangleMesh& mesh, const ImportStats& stats) {
  out.u8(kMesh);
  out.u64(stats.welded_vertices);
  out.u64(stats.skipped_faces);
  out.u8(stats.distinct_positions ? 1 : 0);
  out.u8(stats.own_stl_reader ? 1 : 0);
  out.u64(stats.warnings.size());
  for (const std::string& warning : stats.warnings) out.text(warning);
  out.u64(mesh.positions.size());
  out.bytes(mesh.positions.data(), mesh.positions.size() * sizeof(mesh.positions[0]));
  out.u64(mesh.triangles.size());
  out.bytes(mesh.triangles.data(), mesh.triangles.size() * sizeof(mesh.triangles[0]));
}

void set_child_limits(const ImportLimits& limits) {
  // The soft limit sends SIGXCPU, which ends the child; the hard one a second later, SIGKILL.
  const auto seconds = static_cast<rlim_t>(std::ceil(limits.cpu_seconds));
  const rlimit cpu{seconds, seconds + 1};
  ::setrlimit(RLIMIT_CPU, &cpu);
#ifndef TUMBLE_ADDRESS_SANITIZER
  // (AddressSanitizer reserves terabytes of address space for its shadow: no limit there.)
  const rlim_t bytes = current_address_space() + limits.memory_bytes;
  const rlimit memory{bytes, bytes};
  ::setrlimit(RLIMIT_AS, &memory);
#endif
}

[[noreturn]] void child_main(int fd, pid_t parent, const ImportLimits& limits,
                             const std::function<TriangleMesh(ImportStats&)>& work) {
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) ::_exit(4);  // the parent died before the line above
  reset_child_signals();
  set_child_limits(limits);
  answer(fd, work);
  ::_exit(0);
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

/// Why a child that sent no complete answer ended, as the end of a sentence.
/// `cpu_seconds` is the CPU time the child used: a SIGKILL past the limit is the limit's (the
/// hard limit), one before it someone else's (the kernel's out-of-memory killer, a user).
std::string describe_end(int status, bool timed_out, double cpu_seconds, const ImportLimits& limits,
                         const char* what) {
  const std::string reader = what;
  if (timed_out) return reader + " did not finish reading it in time (it may loop on this file)";
  if (WIFEXITED(status) && WEXITSTATUS(status) == kCannotAnswer) {
    return "the mesh " + reader + " read could not be passed back (no memory or file space left)";
  }
  if (WIFSIGNALED(status)) {
    const int signal = WTERMSIG(status);
    if (signal == SIGXCPU || (signal == SIGKILL && cpu_seconds >= limits.cpu_seconds)) {
      return reader + " used more than " + format_seconds(limits.cpu_seconds) +
             " of CPU time reading it (it may loop on this file)";
    }
    const char* abbreviation = sigabbrev_np(signal);
    const std::string signal_name = abbreviation != nullptr ? std::string("SIG") + abbreviation
                                                            : "signal " + std::to_string(signal);
    if (signal == SIGINT || signal == SIGTERM)
      return "reading it was interrupted (" + signal_name + ")";
    if (signal == SIGKILL) {
      return reader +
             " was killed (SIGKILL) reading it, perhaps by the kernel for want of "
             "memory";
    }
    const char* description = sigdescr_np(signal);
    return reader + " crashed reading it (" + signal_name + ", " +
           (description != nullptr ? description : "unknown signal") +
           "): the file is malformed in a way " + reader + " does not survive";
  }
  return reader + " ended without an answer (exit status " +
         std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ")";
}

/// Waits until the child's end of `pipe` closes (it has ended) or `seconds` pass; false when
/// they passed. Signals for the parent do not cut the wait short.
bool wait_for_end(int pipe, double seconds) {
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double>(seconds));
  while (true) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return false;
    pollfd poll_fd{pipe, POLLIN, 0};
    const int ready =
        ::poll(&poll_fd, 1, static_cast<int>(std::min<long long>(left.count(), 1LL << 30)));
    if (ready < 0 && errno != EINTR) return true;  // cannot wait: reap (blocking) instead
    if (ready <= 0) continue;
    char byte = 0;
    const ssize_t n = ::read(pipe, &byte, 1);
    if (n == 0 || (n < 0 && errno != EINTR && errno != EAGAIN)) return true;
  }
}

/// The parent's side of run_isolated once the child runs: wait for it, reap it, judge.
TriangleMesh receive(const std::filesystem::path& file, const ImportLimits& limits,
                     const char* what, ImportStats& stats, int pipe, int message, pid_t child) {
  const bool timed_out = !wait_for_end(pipe, 2.0 * limits.cpu_seconds + 10.0);
  if (timed_out) ::kill(child, SIGKILL);
  ::close(pipe);
  const ChildEnd end = reap(child, timed_out);
  try {
    TriangleMesh mesh = judge_answer(file, limits, what, stats, message, end);
    ::close(message);
    return mesh;
  } catch (...) {
    ::close(message);
    throw;
  }
}

}  // namespace

std::mutex& import_fork_mutex() {
  static std::mutex mutex;
  return mutex;
}

void reset_child_signals() {
  const rlimit no_core{0, 0};
  ::setrlimit(RLIMIT_CORE, &no_core);
  // Ctrl+C reaches the whole process group: the child then simply ends, and the parent,
  // which saw the signal too, reports the interruption. A crash ends the child by its signal,
  // which the parent names: handlers inherited from the parent (a sanitizer's, a fuzzer's)
  // would report a fault of assimp's as tumble's own, at length, and save crash inputs from
  // inside the child. SIGXFSZ is the parent's choice (ignored: a write past a file size limit
  // fails), kept.
  for (const int signal : {SIGINT, SIGTERM, SIGPIPE, SIGXCPU, SIGSEGV, SIGBUS, SIGFPE, SIGILL}) {
    std::signal(signal, SIG_DFL);
  }
}

std::uint64_t current_address_space() {
  std::ifstream statm("/proc/self/statm");
  std::uint64_t pages = 0;
  statm >> pages;
  return pages * static_cast<std::uint64_t>(::sysconf(_SC_PAGESIZE));
}

std::uint8_t answer(int fd, const std::function<TriangleMesh(ImportStats&)>& work) {
  const PipeWriter out{fd};
  try {
    ImportStats stats;
    const TriangleMesh mesh = work(stats);
    send_mesh(out, mesh, stats);
    return kMesh;
  } catch (const InputError& error) {
    out.u8(kInputError);
    out.text(error.what());
    return kInputError;
  } catch (const std::bad_alloc&) {
    out.u8(kOutOfMemory);
    out.text("");
    return kOutOfMemory;
  } catch (const std::exception& error) {
    out.u8(kFailure);
    out.text(error.what());
  } catch (...) {
    out.u8(kFailure);
    out.text("an unknown exception");
  }
  return kFailure;
}

ChildEnd reap(pid_t child, bool timed_out) {
  ChildEnd end;
  end.timed_out = timed_out;
  rusage usage{};
  while (::wait4(child, &end.status, 0, &usage) < 0 && errno == EINTR) {
  }
  end.cpu_seconds = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                    1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
  return end;
}

TriangleMesh judge_answer(const std::filesystem::path& file, const ImportLimits& limits,
                          const char* what, ImportStats& stats, int message,
                          const std::optional<ChildEnd>& end) {
  ::lseek(message, 0, SEEK_SET);
  MessageReader in{message};
  in.short_read = end && end->timed_out;
  TriangleMesh mesh;
  std::string text;
  const std::uint8_t tag = in.u8();
  if (tag == kMesh) {
    stats.welded_vertices = in.u64();
    stats.skipped_faces = in.u64();
    stats.distinct_positions = in.u8() != 0;
    stats.own_stl_reader = in.u8() != 0;
    const std::uint64_t warnings = in.u64();
    for (std::uint64_t i = 0; i < warnings && !in.short_read; ++i) {
      stats.warnings.push_back(in.text());
    }
    mesh.positions.resize(in.short_read ? 0 : in.u64());
    in.bytes(mesh.positions.data(), mesh.positions.size() * sizeof(mesh.positions[0]));
    mesh.triangles.resize(in.short_read ? 0 : in.u64());
    in.bytes(mesh.triangles.data(), mesh.triangles.size() * sizeof(mesh.triangles[0]));
  } else if (!in.short_read) {
    text = in.text();
  }

  const std::string name = file.string();
  if (in.short_read) {
    const ChildEnd ended = end.value_or(ChildEnd{});
    throw InputError(name + ": " +
                     describe_end(ended.status, ended.timed_out, ended.cpu_seconds, limits, what));
  }
  if (tag == kMesh) return mesh;
  if (tag == kInputError) throw InputError(text);
  if (tag == kOutOfMemory) {
    throw InputError(name + ": " + what + " needs more than " + format_bytes(limits.memory_bytes) +
                     " of memory to read it");
  }
  throw InputError(name + ": " + what + " failed reading it (" + text + ")");
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

TriangleMesh run_isolated(const std::filesystem::path& file, const ImportLimits& limits,
                          const char* what, ImportStats& stats,
                          const std::function<TriangleMesh(ImportStats&)>& work) {
  const auto cannot_start = [&](const char* call) {
    return std::system_error(errno, std::generic_category(),
                             "cannot start reading " + file.string() + " (" + call + ")");
  };
  // One fork at a time: a child forked by another thread between this thread's pipe2 and its
  // close(pipe[1]) below would inherit the write end, and this read would wait for that child
  // to end too. The lock is the parent's; the child (a copy of this thread only) never takes
  // it, nor any other lock a thread of the parent might hold but malloc's, which glibc's fork
  // takes and releases around the copy.
  std::unique_lock fork_lock(import_fork_mutex());
  const int message = ::memfd_create("tumble-import", MFD_CLOEXEC);
  if (message < 0) throw cannot_start("memfd_create");
  std::array<int, 2> pipe{};
  if (::pipe2(pipe.data(), O_CLOEXEC) != 0) {
    const auto error = cannot_start("pipe");
    ::close(message);
    throw error;
  }
  const pid_t parent = ::getpid();
  const pid_t child = ::fork();
  if (child < 0) {
    const auto error = cannot_start("fork");
    for (const int fd : {message, pipe[0], pipe[1]}) ::close(fd);
    throw error;
  }
  if (child == 0) {
    ::close(pipe[0]);  // pipe[1] stays open until the child ends: its closing is the signal
    child_main(message, parent, limits, work);
  }
  ::close(pipe[1]);
  fork_lock.unlock();
  return receive(file, limits, what, stats, pipe[0], message, child);
}

}  // namespace tumble::engine::detail
