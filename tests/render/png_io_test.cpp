#include "render/png_io.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "support/run_command.hpp"

namespace tumble::render {
namespace {

TEST(PngIo, RoundTripsEveryByte) {
  Image image{7, 5, {}};
  for (int i = 0; i < 7 * 5 * 4; ++i) image.rgba.push_back(static_cast<std::uint8_t>(i * 37 + 11));
  const auto dir = tumble::testing::fresh_directory("png_io");
  write_png(dir / "a.png", image);
  const Image back = read_png(dir / "a.png");
  EXPECT_EQ(back.width, 7);
  EXPECT_EQ(back.height, 5);
  EXPECT_EQ(back.rgba, image.rgba);
  std::filesystem::remove_all(dir);
}

TEST(PngIo, ErrorsNameTheFile) {
  EXPECT_THAT(
      [] { read_png("/nonexistent/x.png"); },
      ::testing::ThrowsMessage<std::runtime_error>(::testing::HasSubstr("/nonexistent/x.png")));
  Image image{1, 1, {1, 2, 3, 4}};
  EXPECT_THAT(
      [&] { write_png("/nonexistent/y.png", image); },
      ::testing::ThrowsMessage<std::runtime_error>(::testing::HasSubstr("/nonexistent/y.png")));
}

}  // namespace
}  // namespace tumble::render
