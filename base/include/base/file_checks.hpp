#pragma once
/// @file What a path names, for inputs and outputs named by the user: only regular files are
/// read, and an output never replaces anything but a regular file (nor an input of the command).

#include <sys/stat.h>

#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "base/errors.hpp"

namespace tumble {

/// "a FIFO", "a character device", ... for a file type that is not a regular file.
inline std::string file_kind_name(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISLNK(mode)) return "a symbolic link";
  if (S_ISREG(mode)) return "a regular file";
  return "not a file";
}

/// Why a path could not be used, from an errno: "no such file or directory", "a loop of
/// symbolic links", otherwise strerror in lower case.
inline std::string path_error(int error) {
  if (error == ELOOP) return "a loop of symbolic links";
  std::string text = std::strerror(error);
  if (!text.empty()) text[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(text[0])));
  return text;
}

/// Where an output named `target` is written, after checking it. `target` may be a new name, a
/// regular file (replaced), or a symbolic link to a regular file (its target is replaced, the
/// link stays): the path returned is then the link's target. With `directory`, a directory
/// (or a link to one) takes the place of a regular file. Anything else, a dangling link, a
/// loop of links, or the same file (by device and inode) as one of `inputs` is refused with
/// tumble::InputError "cannot write 'TARGET': ...". What a missing parent folder means is left
/// to the caller.
inline std::filesystem::path checked_output(const std::filesystem::path& target,
                                            const std::vector<std::filesystem::path>& inputs,
                                            bool directory = false) {
  const std::string prefix = "cannot write '" + target.string() + "': ";
  std::filesystem::path clean = target;  // "frames/" names the link "frames", not its target
  if (!clean.has_filename()) clean = clean.parent_path();
  struct stat link {};
  if (::lstat(clean.c_str(), &link) != 0) {
    if (errno == ENOENT || errno == ENOTDIR) return target;  // a new name
    throw InputError(prefix + path_error(errno));
  }
  struct stat status = link;
  if (S_ISLNK(link.st_mode) && ::stat(clean.c_str(), &status) != 0) {
    throw InputError(prefix + (errno == ENOENT ? std::string("it is a symbolic link to nothing")
                                               : path_error(errno)));
  }
  const bool wanted = directory ? S_ISDIR(status.st_mode) : S_ISREG(status.st_mode);
  if (!wanted) {
    throw InputError(prefix + "it is " + (S_ISLNK(link.st_mode) ? "a symbolic link to " : "") +
                     file_kind_name(status.st_mode) + ", not " +
                     (directory ? "a directory" : "a regular file") + " (it is never replaced)");
  }
  for (const std::filesystem::path& input : inputs) {
    struct stat in {};
    if (::stat(input.c_str(), &in) == 0 && in.st_dev == status.st_dev &&
        in.st_ino == status.st_ino) {
      throw InputError(prefix + "it is the input '" + input.string() +
                       "' (an input is never overwritten)");
    }
  }
  if (!S_ISLNK(link.st_mode)) return target;
  std::error_code error;
  std::filesystem::path resolved = std::filesystem::canonical(clean, error);
  if (error) throw InputError(prefix + error.message());
  return resolved;
}

}  // namespace tumble
