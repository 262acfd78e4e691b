#pragma once
/// @file Reading a whole text file named by the user (scenes, scripts), with errors that name it.

#include <cstddef>
#include <filesystem>
#include <string>

namespace tumble::app {

/// The largest scene or script read (64 MiB; real ones are kilobytes).
inline constexpr std::size_t kMaxTextFileBytes = std::size_t{64} << 20;

/// The contents of `file`. Throws tumble::InputError "FILE: ..." naming the expected kind
/// (`what`, "scene file") when it is missing ("cannot open the scene file: no such file"), a
/// loop of symbolic links, a directory, anything else that is not a regular file (a FIFO, a
/// device: refused before it is opened, so nothing blocks or reads forever), larger than
/// kMaxTextFileBytes, or cannot be read.
std::string read_text_file(const std::filesystem::path& file, const std::string& what);

}  // namespace tumble::app
