#pragma once
/// @file Child processes: a program run by its arguments (no shell in between, argv[0] looked up
/// on PATH), its standard streams set up as asked, its output collected or read as it comes, and
/// its end waited for or forced. The one place tumble starts another program (ffmpeg, ffprobe,
/// sbatch, bash).
///
/// Errors, by whose they are to fix:
/// - tumble::InputError: a program that is not on PATH, "PROG not found on PATH", or that cannot
///   be executed, "cannot start PROG: Permission denied"; a file named for a stream that cannot
///   be opened, "cannot start PROG: cannot open 'FILE': REASON".
/// - std::runtime_error: the system failed us (no pipe, no process), "cannot start PROG: pipe:
///   Too many open files".
/// - std::invalid_argument: no program given.

#include <sys/types.h>

#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace tumble {

/// What one standard stream of a child process is connected to.
class ChildStream {
 public:
  enum class Kind { null_device, inherit, pipe, file };

  /// /dev/null: nothing to read, everything written dropped.
  static ChildStream null_device() { return ChildStream(Kind::null_device, {}); }
  /// This process's own stream.
  static ChildStream inherit() { return ChildStream(Kind::inherit, {}); }
  /// A pipe whose other end this process holds (ChildProcess::input, output, error).
  static ChildStream pipe() { return ChildStream(Kind::pipe, {}); }
  /// A file: read from as standard input; created (or truncated) and written as output or error.
  static ChildStream file(std::filesystem::path path) {
    return ChildStream(Kind::file, std::move(path));
  }

  Kind kind() const { return kind_; }
  const std::filesystem::path& path() const { return path_; }

 private:
  ChildStream(Kind kind, std::filesystem::path path) : kind_(kind), path_(std::move(path)) {}
  Kind kind_;
  std::filesystem::path path_;
};

/// How a child process ended.
struct ChildExit {
  int status = -1;  ///< its exit status; -1 when a signal ended it
  int signal = 0;   ///< the signal that ended it; 0 when it exited
  /// As a shell reports it: the exit status, or 128 + the signal.
  int shell_status() const { return signal != 0 ? 128 + signal : status; }
};

/// A running child process. Destroying it while the child runs kills the child (SIGKILL) and
/// reaps it, so no process outlives its owner; the pipes close with it.
class ChildProcess {
 public:
  /// Starts `argv` with its standard input, output and error set up as given (all /dev/null by
  /// default). Throws as the file comment says.
  explicit ChildProcess(const std::vector<std::string>& argv,
                        const ChildStream& input = ChildStream::null_device(),
                        const ChildStream& output = ChildStream::null_device(),
                        const ChildStream& error = ChildStream::null_device());
  ~ChildProcess();
  ChildProcess(ChildProcess&& other) noexcept;
  ChildProcess& operator=(ChildProcess&& other) noexcept;
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  pid_t pid() const { return pid_; }
  /// This process's end of a piped stream (close-on-exec), or -1 when the stream is not a pipe
  /// or the end was closed.
  int input() const { return input_; }
  int output() const { return output_; }
  int error() const { return error_; }

  /// Closes the writing end of a piped standard input: the child reads the end of its input.
  void close_input();

  /// Reads the piped output and error until both close, appending all of the output to `out`
  /// and the error to `err`, of which only about the last `error_tail` bytes are kept (0: all).
  /// `cancel`, when given, is asked about every 100 ms; once it returns true the child is
  /// killed (SIGKILL) and the rest read. Returns whether `cancel` killed it. Streams that are
  /// not pipes are skipped.
  bool collect(std::string& out, std::string& err, const std::function<bool()>& cancel = {},
               std::size_t error_tail = 0);

  /// Waits for the child to end and reaps it; later calls return the same.
  ChildExit wait();

  /// Kills the child (SIGKILL) unless it has been reaped, then waits for it.
  ChildExit kill();

 private:
  void close_all() noexcept;

  pid_t pid_ = -1;
  int input_ = -1;
  int output_ = -1;
  int error_ = -1;
  bool reaped_ = false;
  ChildExit exit_;
};

/// What run_process collected.
struct ProcessResult {
  int status = -1;         ///< its exit status; -1 when a signal ended it
  int signal = 0;          ///< the signal that ended it; 0 when it exited
  bool cancelled = false;  ///< `cancel` said so and the child was killed
  std::string out;         ///< all of its standard output
  std::string err;         ///< the tail of its standard error (about the last kErrorTail bytes)
  /// As a shell reports it: the exit status, or 128 + the signal.
  int shell_status() const { return signal != 0 ? 128 + signal : status; }
};

/// How much of a child's standard error run_process keeps: its last 16 KiB (the end of a long
/// log is what says why it failed).
inline constexpr std::size_t kErrorTail = 16384;

/// Runs `argv` with standard input from /dev/null, collecting its standard output and error,
/// until it ends; `cancel` as ChildProcess::collect takes it. Throws as the file comment says.
ProcessResult run_process(const std::vector<std::string>& argv,
                          const std::function<bool()>& cancel = {});

/// Runs `argv` with this process's standard input, output and error, and waits for it.
ChildExit run_attached(const std::vector<std::string>& argv);

/// This process's environment with glibc's tunable that has malloc advise its blocks as
/// transparent huge pages (`GLIBC_TUNABLES=glibc.malloc.hugetlb=1`, glibc 2.35 and later, the
/// kernel's THP in its default "madvise" mode; elsewhere ignored), unless GLIBC_TUNABLES is set
/// already: for a program started by exec whose heap is large and fresh (a page fault costs
/// microseconds in a virtual machine, and a huge page takes one for 512). Null-terminated; the
/// pointers stay valid while the environment does not change.
std::vector<char*> environment_with_huge_pages();

/// The last two non-empty lines of a tool's standard error on one line, joined by " / " (a tool
/// often names the cause on the line before its generic last one), or "no message on stderr".
std::string last_lines(const std::string& text);

/// The last non-empty line of `text`, without its trailing spaces ("" when there is none).
std::string last_line(const std::string& text);

}  // namespace tumble
