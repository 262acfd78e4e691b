#pragma once
// A move-only owner of a POSIX file descriptor: closed exactly once, when the owner goes or is
// reset; a moved-from owner holds -1 and closes nothing.

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <utility>

namespace tumble::render::detail {

class UniqueFd {
 public:
  UniqueFd() = default;
  explicit UniqueFd(int fd) : fd_(fd) {}
  ~UniqueFd() { reset(); }
  UniqueFd(UniqueFd&& other) noexcept : fd_(std::exchange(other.fd_, -1)) {}
  UniqueFd& operator=(UniqueFd&& other) noexcept {
    if (this != &other) {
      reset();
      fd_ = std::exchange(other.fd_, -1);
    }
    return *this;
  }
  UniqueFd(const UniqueFd&) = delete;
  UniqueFd& operator=(const UniqueFd&) = delete;

  int get() const { return fd_; }
  explicit operator bool() const { return fd_ >= 0; }

  /// Closes the descriptor now (if any).
  void reset() noexcept {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }

 private:
  int fd_ = -1;
};

/// Both ends of a pipe.
struct Pipe {
  UniqueFd read;
  UniqueFd write;
};

/// A close-on-exec pipe; false (errno set, nothing left open) when it cannot be made.
inline bool make_pipe(Pipe& out) {
  int ends[2];
  if (::pipe2(ends, O_CLOEXEC) != 0) return false;
  out.read = UniqueFd(ends[0]);
  out.write = UniqueFd(ends[1]);
  return true;
}

}  // namespace tumble::render::detail
