#pragma once
// PNG files of RGBA images (libpng). Writing favours speed: zlib level 1 and the SUB filter.

#include <filesystem>

#include "base/errors.hpp"
#include "base/image.hpp"

namespace tumble::media {

/// Writes an RGBA8 PNG. Throws tumble::InputError (one line naming the file) when the file
/// cannot be written, std::invalid_argument for an image whose pixels do not match its size,
/// std::runtime_error when libpng runs out of memory.
void write_png(const std::filesystem::path& file, const Image& image, int zlib_level = 1);

/// Reads any PNG as RGBA8 (palette, grey and 16-bit inputs are converted). Throws
/// tumble::InputError naming the file when it cannot be read or is not a valid PNG,
/// std::runtime_error when libpng runs out of memory.
Image read_png(const std::filesystem::path& file);

}  // namespace tumble::media
