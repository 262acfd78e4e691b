#include "app/support/output_folder.hpp"

#include <unistd.h>

#include <fstream>
#include <system_error>

#include <sys/stat.h>

#include "base/errors.hpp"
#include "base/file_checks.hpp"
#include "base/temporary_path.hpp"

namespace tumble::app {
namespace fs = std::filesystem;
using tumble::InputError;

namespace {

/// True when every entry of `dir` is a regular file (not a link) of a kind the commands write:
/// a report, a CSV, a plot, or the kind's report file itself (a part's part.json).
bool holds_only_outputs(const fs::path& dir, const OutputFolderKind& kind) {
  std::error_code error;
  fs::directory_iterator entry(dir, error);
  for (; !error && entry != fs::directory_iterator(); entry.increment(error)) {
    const fs::path extension = entry->path().extension();
    std::error_code type_error;
    if (!entry->is_regular_file(type_error) || entry->is_symlink(type_error) ||
        (extension != ".md" && extension != ".csv" && extension != ".png" && extension != ".svg" &&
         entry->path().filename() != kind.report)) {
      return false;
    }
  }
  return !error;
}

/// True when `dir` is empty or holds an earlier output of this kind and nothing else.
bool replaceable(const fs::path& dir, const OutputFolderKind& kind) {
  std::error_code error;
  if (fs::is_empty(dir, error) && !error) return true;
  if (!holds_only_outputs(dir, kind)) return false;
  std::ifstream report(dir / kind.report);
  std::string first;
  std::getline(report, first);
  return first.starts_with(kind.title) && fs::exists(dir / kind.data, error);
}

/// Where the folder `dir` is written: `dir`, or the folder a symbolic link `dir` points to (the
/// link stays). Throws InputError for a link to something else, a dangling link or a loop.
fs::path real_folder(const fs::path& dir) {
  struct stat link {};
  if (::lstat(dir.c_str(), &link) != 0 || !S_ISLNK(link.st_mode)) return dir;
  try {
    return checked_output(dir, {}, /*directory=*/true);
  } catch (const InputError& error) {
    throw InputError(std::string("-o: ") + error.what());
  }
}

}  // namespace

fs::path start_output_folder(const fs::path& given, const OutputFolderKind& kind) {
  const fs::path dir = real_folder(given);
  std::error_code error;
  if (fs::exists(dir, error)) {
    if (!fs::is_directory(dir, error)) {
      throw InputError("-o: " + given.string() + " exists and is not a directory");
    }
    if (!replaceable(dir, kind)) {
      throw InputError("-o: " + given.string() + " exists and is neither empty nor a previous " +
                       kind.command + " output");
    }
  }
  remove_stale_temporaries(dir);
  const fs::path tmp = temporary_sibling(dir, "tmp");
  fs::remove_all(tmp, error);
  error.clear();
  // The parent must exist: a mistyped path is an error, not a tree of new folders.
  if (!fs::create_directory(tmp, error) || error) {
    throw InputError("-o: cannot create " + given.string() + " (written first as " +
                     tmp.filename().string() + "): " + (error ? error.message() : "it exists"));
  }
  return tmp;
}

void finish_output_folder(const fs::path& tmp, const fs::path& given) {
  const fs::path dir = real_folder(given);
  std::error_code error;
  const fs::path old = temporary_sibling(dir, "old");
  const bool had_old = fs::exists(dir, error);
  if (had_old) {
    fs::rename(dir, old, error);
    if (error)
      throw InputError("-o: " + given.string() + ": cannot replace it: " + error.message());
  }
  fs::rename(tmp, dir, error);
  if (error) {
    const std::string reason = error.message();
    if (had_old) fs::rename(old, dir, error);  // put the earlier output back
    throw InputError("-o: " + given.string() +
                     ": cannot move the new output into place: " + reason);
  }
  if (had_old) fs::remove_all(old, error);
}

WriteError output_write_error(const WriteError& error, const fs::path& tmp, const fs::path& dir) {
  fs::path shown = error.file();
  const fs::path relative = error.file().lexically_relative(tmp);
  if (!relative.empty() && *relative.begin() != "..") shown = dir / relative;
  return WriteError(shown, error.reason() + "; nothing written to '" + dir.string() + "'");
}

}  // namespace tumble::app
