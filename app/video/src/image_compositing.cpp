#include "app/video/image_compositing.hpp"

#include <cstddef>
#include <cstring>

namespace tumble::app {

void fill_grey(Image& image, int width, int height, std::uint8_t grey) {
  image.width = width;
  image.height = height;
  image.rgba.assign(4 * static_cast<std::size_t>(width) * static_cast<std::size_t>(height), grey);
  for (std::size_t i = 3; i < image.rgba.size(); i += 4) image.rgba[i] = 255;
}

void paste_tile(const Image& tile, Image& frame, int x, int y) {
  const std::size_t row_bytes = 4 * static_cast<std::size_t>(tile.width);
  for (int row = 0; row < tile.height; ++row) {
    std::memcpy(frame.rgba.data() + 4 * (static_cast<std::size_t>(y + row) * frame.width + x),
                tile.rgba.data() + static_cast<std::size_t>(row) * row_bytes, row_bytes);
  }
}

}  // namespace tumble::app
