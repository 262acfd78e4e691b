// Whole text files named by the user: only regular files, of bounded size, checked before they
// are opened (a FIFO would block the open, a device would be read forever).
#include "app/support/text_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "base/errors.hpp"
#include "base/file_checks.hpp"

namespace tumble::app {
namespace {

using tumble::InputError;

/// Closes a descriptor when it goes out of scope.
struct FdCloser {
  int fd;
  ~FdCloser() { ::close(fd); }
};

/// Throws unless `status` is a regular file no larger than kMaxTextFileBytes.
void require_readable(const std::filesystem::path& file, const struct stat& status,
                      const std::string& what) {
  if (S_ISDIR(status.st_mode)) {
    throw InputError(file.string() + ": is a directory, expected a " + what);
  }
  if (!S_ISREG(status.st_mode)) {
    throw InputError(file.string() + ": is " + file_kind_name(status.st_mode) +
                     ", not a regular file; expected a " + what);
  }
  if (static_cast<unsigned long long>(status.st_size) > kMaxTextFileBytes) {
    throw InputError(file.string() + ": is " + std::to_string(status.st_size) +
                     " bytes, more than a " + what + " may hold (" +
                     std::to_string(kMaxTextFileBytes >> 20) + " MiB)");
  }
}

}  // namespace

std::string read_text_file(const std::filesystem::path& file, const std::string& what) {
  struct stat status {};
  if (::stat(file.c_str(), &status) != 0) {
    throw InputError(file.string() + ": cannot open the " + what + ": " + path_error(errno));
  }
  require_readable(file, status, what);
  // O_NONBLOCK: should the name have become a FIFO since, the open still returns at once.
  const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) {
    throw InputError(file.string() + ": cannot open the " + what + ": " + path_error(errno));
  }
  const FdCloser closer{fd};
  if (::fstat(fd, &status) != 0) {
    throw InputError(file.string() + ": cannot read the " + what + ": " + path_error(errno));
  }
  require_readable(file, status, what);
  std::string text;
  char buffer[65536];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      throw InputError(file.string() + ": cannot read the " + what + ": " + path_error(errno));
    }
    if (n == 0) break;
    text.append(buffer, static_cast<std::size_t>(n));
    if (text.size() > kMaxTextFileBytes) {  // grew while being read
      throw InputError(file.string() + ": is more than a " + what + " may hold (" +
                       std::to_string(kMaxTextFileBytes >> 20) + " MiB)");
    }
  }
  return text;
}

}  // namespace tumble::app
