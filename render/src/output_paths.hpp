#pragma once
// Temporary names next to an output, so that it appears under its final name only when done.

#include <filesystem>
#include <string>

#include "base/temporary_path.hpp"  // temporary_sibling: the one naming rule

namespace tumble::render::detail {

/// The directory an output goes into ("." for a bare file name).
std::filesystem::path output_directory(const std::filesystem::path& target);

/// Checks that the output's directory exists and is a directory; throws tumble::InputError
/// naming it otherwise.
void require_output_directory(const std::filesystem::path& target);

}  // namespace tumble::render::detail
