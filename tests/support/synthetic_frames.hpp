#pragma once
// Frames drawn on the CPU for the tests of what writes and joins frames (media/): a shaded block
// turning about the centre of a frame over a vertical gradient, so that each frame differs from
// its neighbours and a lossy codec has edges and smooth areas to code.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "base/image.hpp"

namespace tumble::testing {

/// Frame `index` of a `width` x `height` sequence: a block of half the frame's height turned by
/// 0.25 rad a frame about the centre, its shade falling from left to right, over a gradient.
inline tumble::Image turning_block_frame(int width, int height, int index) {
  tumble::Image image;
  image.width = width;
  image.height = height;
  image.rgba.assign(4 * static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 255);
  const double angle = 0.25 * index;
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  const double half_long = 0.35 * height;
  const double half_short = 0.15 * height;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const double dx = x + 0.5 - 0.5 * width;
      const double dy = y + 0.5 - 0.5 * height;
      const double u = c * dx + s * dy;   // along the block
      const double v = -s * dx + c * dy;  // across it
      std::uint8_t* pixel = &image.rgba[4 * (static_cast<std::size_t>(y) * width + x)];
      if (std::abs(u) <= half_long && std::abs(v) <= half_short) {
        const double shade = 0.5 + 0.5 * u / half_long;
        pixel[0] = static_cast<std::uint8_t>(120 + 110 * shade);
        pixel[1] = static_cast<std::uint8_t>(80 + 60 * shade);
        pixel[2] = static_cast<std::uint8_t>(40 + 20 * shade);
      } else {
        const auto grey = static_cast<std::uint8_t>(30 + (100 * y) / height);
        pixel[0] = pixel[1] = grey;
        pixel[2] = static_cast<std::uint8_t>(grey + 20);
      }
    }
  }
  return image;
}

/// Frames [first, first + count) of turning_block_frame.
inline std::vector<tumble::Image> turning_block_frames(int width, int height, int count,
                                                       int first = 0) {
  std::vector<tumble::Image> frames;
  for (int i = first; i < first + count; ++i) {
    frames.push_back(turning_block_frame(width, height, i));
  }
  return frames;
}

}  // namespace tumble::testing
