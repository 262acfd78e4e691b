#include "app/support/output_folder.hpp"

#include <unistd.h>

#include <fstream>
#include <system_error>

#include "engine/input_error.hpp"
#include "tumble/temporary_path.hpp"

namespace tumble::app {
namespace fs = std::filesystem;
using engine::InputError;

namespace {

/// True when `dir` is empty or holds an earlier output of this kind.
bool replaceable(const fs::path& dir, const OutputFolderKind& kind) {
  std::error_code error;
  if (fs::is_empty(dir, error) && !error) return true;
  std::ifstream report(dir / kind.report);
  std::string first;
  std::getline(report, first);
  return first.starts_with(kind.title) && fs::exists(dir / kind.data, error);
}

}  // namespace

fs::path start_output_folder(const fs::path& dir, const OutputFolderKind& kind) {
  std::error_code error;
  if (fs::exists(dir, error)) {
    if (!fs::is_directory(dir, error)) {
      throw InputError("-o: " + dir.string() + " exists and is not a directory");
    }
    if (!replaceable(dir, kind)) {
      throw InputError("-o: " + dir.string() + " exists and is neither empty nor a previous " +
                       kind.command + " output");
    }
  }
  const fs::path tmp = temporary_sibling(dir, "tmp");
  fs::remove_all(tmp, error);
  error.clear();
  // The parent must exist: a mistyped path is an error, not a tree of new folders.
  if (!fs::create_directory(tmp, error) || error) {
    throw InputError("-o: cannot create " + dir.string() + " (written first as " +
                     tmp.filename().string() + "): " + (error ? error.message() : "it exists"));
  }
  return tmp;
}

void finish_output_folder(const fs::path& tmp, const fs::path& dir) {
  std::error_code error;
  const fs::path old = temporary_sibling(dir, "old");
  const bool had_old = fs::exists(dir, error);
  if (had_old) {
    fs::rename(dir, old, error);
    if (error) throw InputError("-o: " + dir.string() + ": cannot replace it: " + error.message());
  }
  fs::rename(tmp, dir, error);
  if (error) {
    const std::string reason = error.message();
    if (had_old) fs::rename(old, dir, error);  // put the earlier output back
    throw InputError("-o: " + dir.string() + ": cannot move the new output into place: " + reason);
  }
  if (had_old) fs::remove_all(old, error);
}

}  // namespace tumble::app
