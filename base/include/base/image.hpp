#pragma once
/// @file An RGBA8 image with top-down rows: what the renderer hands back, the sinks write and the
/// app composes.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace tumble {

/// Tightly packed RGBA8 pixels, row 0 at the top; `rgba.size() == 4 * width * height`.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;

  /// Pointer to the four bytes of pixel (x, y), y counted from the top.
  const std::uint8_t* pixel(int x, int y) const {
    return rgba.data() + 4 * (static_cast<std::size_t>(y) * width + x);
  }
};

}  // namespace tumble
