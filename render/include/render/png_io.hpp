#pragma once
// PNG files of render::Image (libpng). Writing favours speed: zlib level 1 and the SUB filter.

#include <filesystem>

#include "render/image.hpp"

namespace tumble::render {

/// Writes an RGBA8 PNG. Throws std::runtime_error naming the file on failure.
void write_png(const std::filesystem::path& file, const Image& image, int zlib_level = 1);

/// Reads any PNG as RGBA8 (palette, grey and 16-bit inputs are converted). Throws
/// std::runtime_error naming the file on failure.
Image read_png(const std::filesystem::path& file);

}  // namespace tumble::render
