#pragma once
/// @file Whole files written with every write and the close checked, and the error that names
/// the file a write failed on (disk full, file too large, I/O error).

#include <filesystem>
#include <string>
#include <string_view>

#include "base/errors.hpp"

namespace tumble::app {

/// A file that could not be written: the bad-input error of an output ("cannot write 'FILE':
/// REASON"), keeping the file and the reason apart so that a command writing into a temporary
/// folder can name the file by its final name (output_folder.hpp).
class WriteError : public InputError {
 public:
  WriteError(std::filesystem::path file, std::string reason);
  const std::filesystem::path& file() const { return file_; }
  const std::string& reason() const { return reason_; }

 private:
  std::filesystem::path file_;
  std::string reason_;
};

/// Writes `text` to `file` (created, or truncated), checking every write and the close, so that
/// a full disk is never taken for a written file. Throws WriteError with the system's reason
/// ("No space left on device", "File too large").
void write_text_file(const std::filesystem::path& file, std::string_view text);

}  // namespace tumble::app
