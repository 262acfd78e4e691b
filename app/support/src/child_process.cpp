// Child processes: posix_spawnp with stdout and stderr on pipes, read with poll until both
// close, then waited for.
#include "app/support/child_process.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "base/errors.hpp"

extern char** environ;

namespace tumble::app {

namespace {

constexpr std::size_t kStderrTail = 16384;

/// A pipe whose ends close with it.
struct ChildPipe {
  int ends[2] = {-1, -1};
  ChildPipe() {
    if (::pipe2(ends, O_CLOEXEC) != 0) {
      throw std::runtime_error(std::string("cannot start a child process: pipe: ") +
                               std::strerror(errno));
    }
  }
  ~ChildPipe() {
    close_end(0);
    close_end(1);
  }
  ChildPipe(const ChildPipe&) = delete;
  ChildPipe& operator=(const ChildPipe&) = delete;
  void close_end(int end) {
    if (ends[end] >= 0) ::close(ends[end]);
    ends[end] = -1;
  }
};

/// posix_spawn file actions, destroyed with their owner.
struct Actions {
  posix_spawn_file_actions_t actions;
  Actions() { posix_spawn_file_actions_init(&actions); }
  ~Actions() { posix_spawn_file_actions_destroy(&actions); }
  Actions(const Actions&) = delete;
  Actions& operator=(const Actions&) = delete;
};

pid_t spawn(const std::vector<std::string>& argv, ChildPipe& out, ChildPipe& err) {
  std::vector<std::string> copies = argv;
  std::vector<char*> pointers;
  for (std::string& argument : copies) pointers.push_back(argument.data());
  pointers.push_back(nullptr);
  Actions actions;
  posix_spawn_file_actions_addopen(&actions.actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions.actions, out.ends[1], STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions.actions, err.ends[1], STDERR_FILENO);
  pid_t child = -1;
  const int error = ::posix_spawnp(&child, argv.front().c_str(), &actions.actions, nullptr,
                                   pointers.data(), environ);
  if (error == ENOENT) throw InputError(argv.front() + " not found on PATH");
  if (error == EACCES || error == ENOEXEC) {
    throw InputError("cannot run " + argv.front() + ": " + std::strerror(error));
  }
  if (error != 0) {
    throw std::runtime_error("cannot start " + argv.front() + ": " + std::strerror(error));
  }
  out.close_end(1);
  err.close_end(1);
  return child;
}

}  // namespace

ChildResult run_child(const std::vector<std::string>& argv, const std::function<bool()>& cancel) {
  if (argv.empty()) throw std::invalid_argument("run_child: no program");
  ChildPipe out;
  ChildPipe err;
  const pid_t child = spawn(argv, out, err);
  ChildResult result;
  bool killed = false;
  pollfd fds[2] = {{out.ends[0], POLLIN, 0}, {err.ends[0], POLLIN, 0}};
  char buffer[8192];
  while (fds[0].fd >= 0 || fds[1].fd >= 0) {
    if (!killed && cancel && cancel()) {
      ::kill(child, SIGKILL);
      killed = true;
    }
    const int ready = ::poll(fds, 2, 100);
    if (ready < 0 && errno != EINTR) break;
    for (int i = 0; i < 2 && ready > 0; ++i) {
      if (fds[i].fd < 0 || fds[i].revents == 0) continue;
      const ssize_t n = ::read(fds[i].fd, buffer, sizeof buffer);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        fds[i].fd = -1;  // closed: poll ignores negative descriptors
        continue;
      }
      std::string& text = i == 0 ? result.out : result.err;
      text.append(buffer, static_cast<std::size_t>(n));
      if (i == 1 && text.size() > 2 * kStderrTail) text.erase(0, text.size() - kStderrTail);
    }
  }
  int status = 0;
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  result.cancelled = killed;
  result.status = WIFEXITED(status) && !killed ? WEXITSTATUS(status) : -1;
  return result;
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

}  // namespace tumble::app
