#include "media/image_sink.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <utility>

#include "media/png_io.hpp"
#include "support/image_compare.hpp"
#include "support/run_command.hpp"
#include "support/synthetic_frames.hpp"

namespace tumble::media {
namespace {

using tumble::testing::directory_entries;

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

constexpr int kSinkWidth = 96;
constexpr int kSinkHeight = 64;
constexpr int kFrames = 12;

/// kFrames frames of a block turning in the frame.
std::vector<Image> turning_box_frames(int width = kSinkWidth, int height = kSinkHeight) {
  return tumble::testing::turning_block_frames(width, height, kFrames);
}

SinkOptions options(int width = kSinkWidth, int height = kSinkHeight) {
  SinkOptions o;
  o.width = width;
  o.height = height;
  o.fps = 10.0;
  return o;
}

TEST(ImageSink, KindFollowsTheName) {
  EXPECT_EQ(sink_kind("frames/"), SinkKind::kPngSequence);
  EXPECT_EQ(sink_kind("out.mp4"), SinkKind::kMp4);
  EXPECT_EQ(sink_kind("a/b/OUT.WEBM"), SinkKind::kWebm);
  EXPECT_EQ(sink_kind("x.gif"), SinkKind::kGif);
  EXPECT_THAT([] { sink_kind("out.avi"); },
              ThrowsMessage<InputError>(HasSubstr("unknown output 'out.avi'")));
}

TEST(ImageSink, PngSequenceWritesEveryFrameExactly) {
  const auto dir = tumble::testing::fresh_directory("png_sink");
  const auto images = turning_box_frames();
  {
    auto sink = open_image_sink(dir.string() + "/frames/", options());
    for (const Image& image : images) sink->write(image);
    sink->finish();
    EXPECT_EQ(sink->frames(), static_cast<std::size_t>(kFrames));
  }
  EXPECT_EQ(directory_entries(dir), std::vector<std::string>{"frames"});
  ASSERT_EQ(directory_entries(dir / "frames").size(), static_cast<std::size_t>(kFrames));
  for (int i = 0; i < kFrames; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%06d.png", i);
    const Image back = read_png(dir / "frames" / name);
    ASSERT_EQ(back.width, kSinkWidth);
    ASSERT_EQ(back.height, kSinkHeight);
    EXPECT_EQ(back.rgba, images[static_cast<std::size_t>(i)].rgba) << name;
  }
  std::filesystem::remove_all(dir);
}

TEST(ImageSink, UnfinishedPngSequenceLeavesNothing) {
  const auto dir = tumble::testing::fresh_directory("png_abort");
  const auto images = turning_box_frames();
  {
    auto sink = open_image_sink(dir / "frames/", options());
    sink->write(images[0]);
    sink->write(images[1]);
  }
  EXPECT_TRUE(directory_entries(dir).empty());
  std::filesystem::remove_all(dir);
}

TEST(ImageSink, Mp4IsH264WithEveryFrameAndMatchesThePngs) {
  const auto dir = tumble::testing::fresh_directory("mp4_sink");
  const auto images = turning_box_frames();
  auto sink = open_image_sink(dir / "out.mp4", options());
  for (const Image& image : images) sink->write(image);
  sink->finish();
  EXPECT_EQ(directory_entries(dir), std::vector<std::string>{"out.mp4"});
  EXPECT_EQ(tumble::testing::probe_video(dir / "out.mp4"), "h264,96,64,12");

  // Decode frame 5 and compare with the frame written (lossy yuv420p: small mean error).
  const auto decoded = dir / "frame5.png";
  const auto result = tumble::testing::run_command(
      "ffmpeg -v error -y -i '" + (dir / "out.mp4").string() +
      "' -vf 'select=eq(n\\,5)' -vframes 1 '" + decoded.string() + "'");
  ASSERT_EQ(result.status, 0) << result.err;
  const Image frame = read_png(decoded);
  ASSERT_EQ(frame.width, kSinkWidth);
  const double error = testing::mean_difference(frame, images[5]);
  EXPECT_LT(error, 4.0);
  // ...and it is frame 5, not a neighbour.
  EXPECT_LT(error, testing::mean_difference(frame, images[4]));
  EXPECT_LT(error, testing::mean_difference(frame, images[6]));
  std::filesystem::remove_all(dir);
}

TEST(ImageSink, WebmAndGifHaveEveryFrame) {
  const auto dir = tumble::testing::fresh_directory("webm_gif_sink");
  const auto images = turning_box_frames();
  for (const char* name : {"out.webm", "out.gif"}) {
    auto sink = open_image_sink(dir / name, options());
    for (const Image& image : images) sink->write(image);
    sink->finish();
  }
  EXPECT_EQ(directory_entries(dir), (std::vector<std::string>{"out.gif", "out.webm"}));
  EXPECT_EQ(tumble::testing::probe_video(dir / "out.webm"), "vp9,96,64,12");
  EXPECT_EQ(tumble::testing::probe_video(dir / "out.gif"), "gif,96,64,12");
  std::filesystem::remove_all(dir);
}

TEST(ImageSink, UnfinishedVideoLeavesNothing) {
  const auto dir = tumble::testing::fresh_directory("mp4_abort");
  const auto images = turning_box_frames();
  {
    auto sink = open_image_sink(dir / "out.mp4", options());
    for (const Image& image : images) sink->write(image);
  }
  EXPECT_TRUE(directory_entries(dir).empty());
  std::filesystem::remove_all(dir);
}

TEST(ImageSink, UnknownExtensionFailsBeforeRendering) {
  EXPECT_THAT([] { open_image_sink("/tmp/out.avi", options()); },
              ThrowsMessage<InputError>(HasSubstr("unknown output '/tmp/out.avi'")));
}

TEST(ImageSink, MissingOrUnwritableDirectoryIsNamed) {
  EXPECT_THAT([] { open_image_sink("/nonexistent/dir/out.mp4", options()); },
              ThrowsMessage<InputError>(HasSubstr("'/nonexistent/dir' does not exist")));
  EXPECT_THAT([] { open_image_sink("/nonexistent/dir/frames/", options()); },
              ThrowsMessage<InputError>(HasSubstr("'/nonexistent/dir' does not exist")));
  // An existing directory we may not write to (root may write anywhere but sysfs).
  std::filesystem::path locked = "/sys";
  if (::geteuid() != 0) {
    locked = tumble::testing::fresh_directory("locked");
    std::filesystem::permissions(
        locked, std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
  }
  EXPECT_THAT([&] { open_image_sink(locked / "out.mp4", options()); },
              ThrowsMessage<InputError>(HasSubstr("directory '" + locked.string() + "'")));
  EXPECT_THAT([&] { open_image_sink(locked / "frames/", options()); },
              ThrowsMessage<InputError>(HasSubstr("'" + locked.string() + "'")));
  if (locked != "/sys") {
    std::filesystem::permissions(locked, std::filesystem::perms::owner_all);
    std::filesystem::remove_all(locked);
  }
}

TEST(ImageSink, FfmpegFailureIsOneLineAndLeavesNoFile) {
  // yuv420p needs even sizes: libx264 refuses 97x64 once the first frame arrives.
  const auto dir = tumble::testing::fresh_directory("mp4_odd");
  const auto images = turning_box_frames(97, 64);
  auto sink = open_image_sink(dir / "out.mp4", options(97, 64));
  EXPECT_THAT(
      [&] {
        for (const Image& image : images) sink->write(image);
        sink->finish();
      },
      ThrowsMessage<InputError>(::testing::AllOf(HasSubstr("ffmpeg failed writing"),
                                                 HasSubstr("width not divisible by 2"),
                                                 ::testing::Not(HasSubstr("\n")))));
  sink.reset();
  EXPECT_TRUE(directory_entries(dir).empty());
  std::filesystem::remove_all(dir);
}

TEST(ImageSink, MissingFfmpegIsReportedAtOpen) {
  const auto dir = tumble::testing::fresh_directory("no_ffmpeg");
  const std::string path = std::getenv("PATH") ? std::getenv("PATH") : "";
  ::setenv("PATH", "/nonexistent", 1);
  EXPECT_THAT([&] { open_image_sink(dir / "out.mp4", options()); },
              ThrowsMessage<InputError>(HasSubstr("ffmpeg not found on PATH")));
  ::setenv("PATH", path.c_str(), 1);
  EXPECT_TRUE(directory_entries(dir).empty());
  std::filesystem::remove_all(dir);
}

TEST(ImageSink, WrongFrameSizeIsRejected) {
  const auto dir = tumble::testing::fresh_directory("wrong_size");
  auto sink = open_image_sink(dir / "frames/", options());
  Image small{8, 8, std::vector<std::uint8_t>(256, 0)};
  EXPECT_THAT([&] { sink->write(small); },
              ThrowsMessage<std::invalid_argument>(HasSubstr("frame is 8x8, expected 96x64")));
  sink.reset();
  EXPECT_TRUE(directory_entries(dir).empty());
  std::filesystem::remove_all(dir);
}

/// A frame no flip or mirror maps onto itself: a dark background, a bright block in the
/// top-left corner and a mid-grey bar along the bottom, each placed by frame number.
Image asymmetric_frame(int index) {
  Image image;
  image.width = kSinkWidth;
  image.height = kSinkHeight;
  image.rgba.assign(4 * static_cast<std::size_t>(kSinkWidth * kSinkHeight), 0);
  for (int y = 0; y < kSinkHeight; ++y) {
    for (int x = 0; x < kSinkWidth; ++x) {
      std::uint8_t* pixel = &image.rgba[4 * static_cast<std::size_t>(y * kSinkWidth + x)];
      std::uint8_t value = 20;
      if (y < 24 && x >= 8 * index && x < 8 * index + 24) value = 230;  // top, moving right
      if (y >= kSinkHeight - 12) value = 128;                           // bottom bar
      pixel[0] = pixel[1] = pixel[2] = value;
      pixel[3] = 255;
    }
  }
  return image;
}

Image flipped(const Image& image) {
  Image out = image;
  const std::size_t row = 4 * static_cast<std::size_t>(image.width);
  for (int y = 0; y < image.height; ++y) {
    std::copy_n(image.rgba.begin() + static_cast<std::ptrdiff_t>(row * y), row,
                out.rgba.begin() + static_cast<std::ptrdiff_t>(row * (image.height - 1 - y)));
  }
  return out;
}

TEST(ImageSink, Mp4FramesAreUprightAndInOrder) {
  const auto dir = tumble::testing::fresh_directory("mp4_upright");
  std::vector<Image> images;
  for (int i = 0; i < 6; ++i) images.push_back(asymmetric_frame(i));
  auto sink = open_image_sink(dir / "out.mp4", options());
  // As `tumble render` writes: one image, drawn into again after each write_taking().
  Image canvas;
  for (const Image& image : images) {
    canvas.width = image.width;
    canvas.height = image.height;
    canvas.rgba.resize(image.rgba.size());
    std::copy(image.rgba.begin(), image.rgba.end(), canvas.rgba.begin());
    sink->write_taking(canvas);
    EXPECT_EQ(canvas.width, kSinkWidth);
  }
  sink->finish();
  EXPECT_EQ(tumble::testing::probe_video(dir / "out.mp4"), "h264,96,64,6");
  for (int n : {0, 3}) {
    const auto decoded = dir / ("frame" + std::to_string(n) + ".png");
    const auto result = tumble::testing::run_command(
        "ffmpeg -v error -y -i '" + (dir / "out.mp4").string() + "' -vf 'select=eq(n\\," +
        std::to_string(n) + ")' -vframes 1 '" + decoded.string() + "'");
    ASSERT_EQ(result.status, 0) << result.err;
    const Image frame = read_png(decoded);
    ASSERT_EQ(frame.width, kSinkWidth);
    ASSERT_EQ(frame.height, kSinkHeight);
    const double error = testing::mean_difference(frame, images[n]);
    EXPECT_LT(error, 4.0) << "frame " << n;
    // Upside down, the bar and the block trade places: far more than the coding error.
    EXPECT_GT(testing::mean_difference(frame, flipped(images[n])), 10.0 * error + 20.0);
    // The block moves 8 px a frame: a neighbour is further off than the coding error.
    EXPECT_LT(error, testing::mean_difference(frame, images[n + 1]));
  }
  std::filesystem::remove_all(dir);
}

TEST(ImageSink, FramesAreNotDrawnIntoBeforeFfmpegHasReadThem) {
  // As `tumble render` writes, drawing into each recycled buffer at once: flat frames whose
  // grey level counts them. The sink splices frames into ffmpeg's pipe (their pages, not a
  // copy), so a buffer handed back too early would be drawn into while ffmpeg has yet to read
  // it, and that frame would end in a later frame's level. Frames larger than the pipe (720p,
  // 3.7 MB against 1 MiB) and smaller (several in the pipe at once).
  constexpr int kLevels = 24;
  for (const auto& [width, height] : {std::pair{1280, 720}, std::pair{320, 180}}) {
    const auto dir = tumble::testing::fresh_directory("mp4_spliced");
    auto sink = open_image_sink(dir / "out.mp4", options(width, height));
    Image canvas;
    for (int k = 0; k < kLevels; ++k) {
      canvas.width = width;
      canvas.height = height;
      canvas.rgba.resize(4 * static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
      const auto level = static_cast<std::uint8_t>(10 * k);
      for (std::size_t i = 0; i < canvas.rgba.size(); i += 4) {
        canvas.rgba[i] = canvas.rgba[i + 1] = canvas.rgba[i + 2] = level;
        canvas.rgba[i + 3] = 255;
      }
      sink->write_taking(canvas);
    }
    sink->finish();
    const auto grey = dir / "frames.grey";
    const auto result =
        tumble::testing::run_command("ffmpeg -v error -y -i '" + (dir / "out.mp4").string() +
                                     "' -f rawvideo -pix_fmt gray '" + grey.string() + "'");
    ASSERT_EQ(result.status, 0) << result.err;
    std::ifstream in(grey, std::ios::binary);
    const std::vector<char> bytes((std::istreambuf_iterator<char>(in)),
                                  std::istreambuf_iterator<char>());
    const std::size_t frame = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    ASSERT_EQ(bytes.size(), kLevels * frame) << width << "x" << height;
    for (int k = 0; k < kLevels; ++k) {
      int low = 255, high = 0;
      for (std::size_t i = k * frame; i < (k + 1) * frame; ++i) {
        const int v = static_cast<unsigned char>(bytes[i]);
        low = std::min(low, v);
        high = std::max(high, v);
      }
      // Flat frames survive the encoding but for the YUV rounding (levels are 10 apart).
      EXPECT_GE(low, 10 * k - 3) << width << "x" << height << " frame " << k;
      EXPECT_LE(high, 10 * k + 3) << width << "x" << height << " frame " << k;
    }
    std::filesystem::remove_all(dir);
  }
}

}  // namespace
}  // namespace tumble::media
