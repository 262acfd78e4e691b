// Whole files written through the system calls themselves, whose every error is seen: a
// buffered stream can report a full disk only at a flush or close nobody checked.
#include "app/support/file_write.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <utility>

namespace tumble::app {

WriteError::WriteError(std::filesystem::path file, std::string reason)
    : InputError("cannot write '" + file.string() + "': " + reason),
      file_(std::move(file)),
      reason_(std::move(reason)) {}

void write_text_file(const std::filesystem::path& file, std::string_view text) {
  const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw WriteError(file, std::strerror(errno));
  while (!text.empty()) {
    const ssize_t written = ::write(fd, text.data(), text.size());
    if (written < 0 && errno == EINTR) continue;
    if (written <= 0) {
      // write() returns 0 only for a zero-byte request; treat it as the device being full.
      const std::string reason = std::strerror(written < 0 ? errno : ENOSPC);
      ::close(fd);
      throw WriteError(file, reason);
    }
    text.remove_prefix(static_cast<std::size_t>(written));
  }
  // close() reports what a file system defers (NFS, quotas); EINTR still closed the file.
  if (::close(fd) != 0 && errno != EINTR) throw WriteError(file, std::strerror(errno));
}

}  // namespace tumble::app
