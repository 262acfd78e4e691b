#include "media/png_io.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "support/run_command.hpp"

namespace tumble::media {
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
  EXPECT_THAT([] { read_png("/nonexistent/x.png"); },
              ::testing::ThrowsMessage<InputError>(::testing::HasSubstr("/nonexistent/x.png")));
  Image image{1, 1, {1, 2, 3, 4}};
  EXPECT_THAT([&] { write_png("/nonexistent/y.png", image); },
              ::testing::ThrowsMessage<InputError>(::testing::HasSubstr("/nonexistent/y.png")));
}

TEST(PngIo, NotAPngIsBadInputAndAMalformedImageIsTheCallers) {
  const auto dir = tumble::testing::fresh_directory("png_io_errors");
  { std::ofstream(dir / "text.png") << "not a PNG at all\n"; }
  EXPECT_THAT([&] { read_png(dir / "text.png"); },
              ::testing::ThrowsMessage<InputError>(::testing::AllOf(
                  ::testing::HasSubstr("cannot read PNG '" + (dir / "text.png").string() + "'"),
                  ::testing::HasSubstr("Not a PNG file"))));
  const Image short_pixels{2, 2, {1, 2, 3, 4}};
  EXPECT_THAT([&] { write_png(dir / "short.png", short_pixels); },
              ::testing::ThrowsMessage<std::invalid_argument>(
                  ::testing::HasSubstr("'" + (dir / "short.png").string() + "': malformed image")));
  EXPECT_FALSE(std::filesystem::exists(dir / "short.png"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace tumble::media
