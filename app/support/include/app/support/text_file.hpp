#pragma once
/// @file Reading a whole text file named by the user (scenes, scripts), with errors that name it.

#include <filesystem>
#include <string>

namespace tumble::app {

/// The contents of `file`. Throws engine::InputError "FILE: ..." when it is a directory, cannot
/// be opened or cannot be read; `what` names the expected kind in the message ("scene file").
std::string read_text_file(const std::filesystem::path& file, const std::string& what);

}  // namespace tumble::app
