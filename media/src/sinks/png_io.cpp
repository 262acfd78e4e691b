#include "media/png_io.hpp"

#include <png.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/errors.hpp"

namespace tumble::media {

namespace {

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

/// libpng reports errors through longjmp by default; turn them into a stored message instead.
struct ErrorState {
  std::string message;
};

[[noreturn]] void on_png_error(png_structp png, png_const_charp message) {
  auto* state = static_cast<ErrorState*>(png_get_error_ptr(png));
  state->message = message;
  png_longjmp(png, 1);
}

void on_png_warning(png_structp, png_const_charp) {}

}  // namespace

void write_png(const std::filesystem::path& file, const Image& image, int zlib_level) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgba.size() != 4 * static_cast<std::size_t>(image.width) * image.height) {
    throw std::invalid_argument("cannot write PNG '" + file.string() + "': malformed image");
  }
  File out(std::fopen(file.c_str(), "wb"));
  if (!out) {
    throw InputError("cannot write PNG '" + file.string() + "': " + std::strerror(errno));
  }
  ErrorState state;
  png_structp png =
      png_create_write_struct(PNG_LIBPNG_VER_STRING, &state, on_png_error, on_png_warning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (info == nullptr) {
    png_destroy_write_struct(&png, nullptr);
    throw std::runtime_error("cannot write PNG '" + file.string() + "': out of memory");
  }
  std::vector<png_bytep> rows(static_cast<std::size_t>(image.height));
  for (int y = 0; y < image.height; ++y) {
    rows[static_cast<std::size_t>(y)] = const_cast<png_bytep>(image.pixel(0, y));
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw InputError("cannot write PNG '" + file.string() + "': " + state.message);
  }
  png_init_io(png, out.get());
  png_set_compression_level(png, zlib_level);
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.width),
               static_cast<png_uint_32>(image.height), 8, PNG_COLOR_TYPE_RGBA, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  png_write_image(png, rows.data());
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  if (std::fflush(out.get()) != 0 || std::ferror(out.get())) {
    throw InputError("cannot write PNG '" + file.string() + "': " + std::strerror(errno));
  }
}

Image read_png(const std::filesystem::path& file) {
  File in(std::fopen(file.c_str(), "rb"));
  if (!in) {
    throw InputError("cannot read PNG '" + file.string() + "': " + std::strerror(errno));
  }
  ErrorState state;
  png_structp png =
      png_create_read_struct(PNG_LIBPNG_VER_STRING, &state, on_png_error, on_png_warning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (info == nullptr) {
    png_destroy_read_struct(&png, nullptr, nullptr);
    throw std::runtime_error("cannot read PNG '" + file.string() + "': out of memory");
  }
  Image image;
  std::vector<png_bytep> rows;
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    throw InputError("cannot read PNG '" + file.string() + "': " + state.message);
  }
  png_init_io(png, in.get());
  png_read_info(png, info);
  // Normalise every colour type and depth to RGBA8.
  png_set_expand(png);
  png_set_strip_16(png);
  png_set_gray_to_rgb(png);
  png_set_add_alpha(png, 0xff, PNG_FILLER_AFTER);
  png_read_update_info(png, info);
  image.width = static_cast<int>(png_get_image_width(png, info));
  image.height = static_cast<int>(png_get_image_height(png, info));
  image.rgba.resize(4 * static_cast<std::size_t>(image.width) * image.height);
  rows.resize(static_cast<std::size_t>(image.height));
  for (int y = 0; y < image.height; ++y) {
    rows[static_cast<std::size_t>(y)] =
        image.rgba.data() + 4 * static_cast<std::size_t>(y) * image.width;
  }
  png_read_image(png, rows.data());
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  return image;
}

}  // namespace tumble::media
