#pragma once
/// @file Frames composed on the CPU from images rendered apart (`tumble compare`'s grid): a
/// frame cleared to a grey, and tiles copied into it.

#include <cstdint>

#include "base/image.hpp"

namespace tumble::app {

/// Resizes `image` to `width` x `height` and fills it with an opaque `grey`.
void fill_grey(Image& image, int width, int height, std::uint8_t grey);

/// Copies `tile` into `frame` with its top-left corner at (x, y); the tile must fit.
void paste_tile(const Image& tile, Image& frame, int x, int y);

}  // namespace tumble::app
