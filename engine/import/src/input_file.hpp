#pragma once
// What the engine's mesh readers share about the file they read: the one-line error naming it,
// a C stream closed on every path, and the extension compared without case.

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "base/errors.hpp"

namespace tumble::engine::detail {

/// Throws the InputError "<file>: <problem>".
[[noreturn]] inline void fail(const std::filesystem::path& file, const std::string& problem) {
  throw InputError(file.string() + ": " + problem);
}

struct CloseFile {
  void operator()(std::FILE* stream) const { std::fclose(stream); }
};

/// A stream from std::fopen, closed when it goes out of scope (null when the open failed).
using CFile = std::unique_ptr<std::FILE, CloseFile>;

/// The file's extension in lower case, with its dot (".stl"), or "".
inline std::string lower_extension(const std::filesystem::path& file) {
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

}  // namespace tumble::engine::detail
