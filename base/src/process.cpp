// Child processes: posix_spawnp with the streams set up by file actions (pipes and files opened
// here, close-on-exec, and dup2'ed onto the child's 0, 1 and 2), read with poll, reaped with
// waitpid.
#include "base/process.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <utility>

#include "base/errors.hpp"

extern char** environ;

namespace tumble {

namespace {

/// A descriptor closed with its owner unless released.
struct OwnedFd {
  int fd = -1;
  OwnedFd() = default;
  OwnedFd(const OwnedFd&) = delete;
  OwnedFd& operator=(const OwnedFd&) = delete;
  ~OwnedFd() { reset(); }
  void reset() {
    if (fd >= 0) ::close(fd);
    fd = -1;
  }
  int release() { return std::exchange(fd, -1); }
};

/// posix_spawn file actions, destroyed with their owner.
struct SpawnActions {
  posix_spawn_file_actions_t actions;
  SpawnActions() { posix_spawn_file_actions_init(&actions); }
  ~SpawnActions() { posix_spawn_file_actions_destroy(&actions); }
  SpawnActions(const SpawnActions&) = delete;
  SpawnActions& operator=(const SpawnActions&) = delete;
};

/// Whether a posix_spawnp error is the user's to fix: no such program on PATH, or one that cannot
/// be executed. Anything else (fork failing for want of memory or processes) is the system's.
bool spawn_error_is_input(int error) {
  return error == ENOENT || error == EACCES || error == ENOEXEC || error == ENOTDIR ||
         error == ELOOP || error == ENAMETOOLONG;
}

/// One stream's set-up: the child's end is dup2'ed onto `target`; this process keeps `parent`.
struct StreamEnds {
  OwnedFd child;
  OwnedFd parent;
};

/// Opens what `stream` asks for as the child's descriptor `target` and adds the file action.
void set_up(const ChildStream& stream, int target, const std::string& program,
            SpawnActions& actions, StreamEnds& ends) {
  switch (stream.kind()) {
    case ChildStream::Kind::inherit:
      return;
    case ChildStream::Kind::null_device:
      posix_spawn_file_actions_addopen(&actions.actions, target, "/dev/null",
                                       target == STDIN_FILENO ? O_RDONLY : O_WRONLY, 0);
      return;
    case ChildStream::Kind::pipe: {
      int pipe_ends[2];
      if (::pipe2(pipe_ends, O_CLOEXEC) != 0) {
        throw std::runtime_error("cannot start " + program + ": pipe: " + std::strerror(errno));
      }
      const bool reads = target == STDIN_FILENO;
      ends.child.fd = pipe_ends[reads ? 0 : 1];
      ends.parent.fd = pipe_ends[reads ? 1 : 0];
      break;
    }
    case ChildStream::Kind::file: {
      const int flags = target == STDIN_FILENO ? O_RDONLY : O_WRONLY | O_CREAT | O_TRUNC;
      ends.child.fd = ::open(stream.path().c_str(), flags | O_CLOEXEC, 0644);
      if (ends.child.fd < 0) {
        throw InputError("cannot start " + program + ": cannot open '" + stream.path().string() +
                         "': " + std::strerror(errno));
      }
      break;
    }
  }
  posix_spawn_file_actions_adddup2(&actions.actions, ends.child.fd, target);
}

/// Reads what is there on `fd` into `text`; false once the stream has ended (or failed).
bool read_some(int fd, std::string& text) {
  char buffer[8192];
  const ssize_t n = ::read(fd, buffer, sizeof buffer);
  if (n < 0 && (errno == EINTR || errno == EAGAIN)) return true;
  if (n <= 0) return false;
  text.append(buffer, static_cast<std::size_t>(n));
  return true;
}

ChildExit exit_of(int status) {
  ChildExit exit;
  if (WIFEXITED(status)) exit.status = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) exit.signal = WTERMSIG(status);
  return exit;
}

}  // namespace

ChildProcess::ChildProcess(const std::vector<std::string>& argv, const ChildStream& input,
                           const ChildStream& output, const ChildStream& error) {
  if (argv.empty() || argv.front().empty()) {
    throw std::invalid_argument("ChildProcess: no program");
  }
  const std::string& program = argv.front();
  SpawnActions actions;
  StreamEnds ends[3];
  set_up(input, STDIN_FILENO, program, actions, ends[0]);
  set_up(output, STDOUT_FILENO, program, actions, ends[1]);
  set_up(error, STDERR_FILENO, program, actions, ends[2]);
  std::vector<std::string> copies = argv;
  std::vector<char*> pointers;
  for (std::string& argument : copies) pointers.push_back(argument.data());
  pointers.push_back(nullptr);
  pid_t child = -1;
  const int spawned =
      ::posix_spawnp(&child, program.c_str(), &actions.actions, nullptr, pointers.data(), environ);
  if (spawned == ENOENT) throw InputError(program + " not found on PATH");
  if (spawned != 0) {
    const std::string message = "cannot start " + program + ": " + std::strerror(spawned);
    if (spawn_error_is_input(spawned)) throw InputError(message);
    throw std::runtime_error(message);
  }
  // The child's ends close here (`ends` goes), so it sees the end of its input once ours
  // closes, and we see the end of its output once it exits.
  pid_ = child;
  input_ = ends[0].parent.release();
  output_ = ends[1].parent.release();
  error_ = ends[2].parent.release();
}

ChildProcess::~ChildProcess() {
  if (pid_ > 0 && !reaped_) kill();
  close_all();
}

ChildProcess::ChildProcess(ChildProcess&& other) noexcept
    : pid_(std::exchange(other.pid_, -1)),
      input_(std::exchange(other.input_, -1)),
      output_(std::exchange(other.output_, -1)),
      error_(std::exchange(other.error_, -1)),
      reaped_(other.reaped_),
      exit_(other.exit_) {}

ChildProcess& ChildProcess::operator=(ChildProcess&& other) noexcept {
  if (this != &other) {
    if (pid_ > 0 && !reaped_) kill();
    close_all();
    pid_ = std::exchange(other.pid_, -1);
    input_ = std::exchange(other.input_, -1);
    output_ = std::exchange(other.output_, -1);
    error_ = std::exchange(other.error_, -1);
    reaped_ = other.reaped_;
    exit_ = other.exit_;
  }
  return *this;
}

void ChildProcess::close_all() noexcept {
  for (int* fd : {&input_, &output_, &error_}) {
    if (*fd >= 0) ::close(*fd);
    *fd = -1;
  }
}

void ChildProcess::close_input() {
  if (input_ >= 0) ::close(input_);
  input_ = -1;
}

bool ChildProcess::collect(std::string& out, std::string& err, const std::function<bool()>& cancel,
                           std::size_t error_tail) {
  bool killed = false;
  pollfd fds[2] = {{output_, POLLIN, 0}, {error_, POLLIN, 0}};
  std::string* texts[2] = {&out, &err};
  while (fds[0].fd >= 0 || fds[1].fd >= 0) {
    if (!killed && cancel && cancel()) {
      if (pid_ > 0 && !reaped_) ::kill(pid_, SIGKILL);
      killed = true;
    }
    const int ready = ::poll(fds, 2, cancel ? 100 : -1);
    if (ready < 0 && errno != EINTR) break;
    for (int i = 0; i < 2 && ready > 0; ++i) {
      if (fds[i].fd < 0 || fds[i].revents == 0) continue;
      if (!read_some(fds[i].fd, *texts[i])) fds[i].fd = -1;  // ended: poll skips it now
    }
    if (error_tail > 0 && err.size() > 2 * error_tail) err.erase(0, err.size() - error_tail);
  }
  return killed;
}

ChildExit ChildProcess::wait() {
  if (pid_ <= 0 || reaped_) return exit_;
  int status = 0;
  pid_t waited = 0;
  do {
    waited = ::waitpid(pid_, &status, 0);
  } while (waited < 0 && errno == EINTR);
  reaped_ = true;
  exit_ = waited == pid_ ? exit_of(status) : ChildExit{};
  return exit_;
}

ChildExit ChildProcess::kill() {
  if (pid_ > 0 && !reaped_) ::kill(pid_, SIGKILL);
  return wait();
}

ProcessResult run_process(const std::vector<std::string>& argv,
                          const std::function<bool()>& cancel) {
  ChildProcess child(argv, ChildStream::null_device(), ChildStream::pipe(), ChildStream::pipe());
  ProcessResult result;
  result.cancelled = child.collect(result.out, result.err, cancel, kErrorTail);
  const ChildExit exit = child.wait();
  result.status = exit.status;
  result.signal = exit.signal;
  return result;
}

ChildExit run_attached(const std::vector<std::string>& argv) {
  ChildProcess child(argv, ChildStream::inherit(), ChildStream::inherit(), ChildStream::inherit());
  return child.wait();
}

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

std::vector<char*> environment_with_huge_pages() {
  static std::string tunable = "GLIBC_TUNABLES=glibc.malloc.hugetlb=1";
  std::vector<char*> entries;
  bool tuned = false;
  for (char** entry = environ; *entry != nullptr; ++entry) {
    tuned = tuned || std::strncmp(*entry, "GLIBC_TUNABLES=", 15) == 0;
    entries.push_back(*entry);
  }
  if (!tuned) entries.push_back(tunable.data());
  entries.push_back(nullptr);
  return entries;
}

std::string last_line(const std::string& text) {
  std::size_t end = text.size();
  while (end > 0 && (text[end - 1] == '\n' || text[end - 1] == ' ')) --end;
  const std::size_t newline = end == 0 ? std::string::npos : text.rfind('\n', end - 1);
  const std::size_t begin = newline == std::string::npos ? 0 : newline + 1;
  return text.substr(begin, end - begin);
}

}  // namespace tumble
