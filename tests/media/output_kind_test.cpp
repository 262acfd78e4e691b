// What an output name asks for and the names of a sequence's frames (media/output_kind.hpp).
#include "media/output_kind.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "base/errors.hpp"
#include "support/run_command.hpp"

namespace tumble::media {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

TEST(OutputKind, FormatNamesAreThoseOfTheExtensions) {
  EXPECT_EQ(format_name(sink_kind("frames/")), "png");
  EXPECT_EQ(format_name(sink_kind("a.MP4")), "mp4");
  EXPECT_EQ(format_name(sink_kind("a.webm")), "webm");
  EXPECT_EQ(format_name(sink_kind("a.gif")), "gif");
}

TEST(OutputKind, FrameNamesAndTheirNumbers) {
  EXPECT_EQ(frame_file_name(0), "frame_000000.png");
  EXPECT_EQ(frame_file_name(123456), "frame_123456.png");
  EXPECT_EQ(frame_file_name(1234567), "frame_1234567.png");
  char printed[32];
  std::snprintf(printed, sizeof printed, kFramePattern, 42);  // as ffmpeg fills the pattern
  EXPECT_EQ(printed, frame_file_name(42));
  for (const std::size_t index : {0u, 7u, 999999u, 1000000u}) {
    EXPECT_EQ(frame_file_index(frame_file_name(index)), index);
  }
  for (const char* other : {"frame_12.png", "frame_00001x.png", "frame_000001.jpg", "part.json",
                            "frame_.png", "xframe_000001.png"}) {
    EXPECT_EQ(frame_file_index(other), std::nullopt) << other;
  }
}

TEST(OutputKind, AFolderOfFramesMayBeReplacedAndNoOther) {
  const auto dir = tumble::testing::fresh_directory("output_kind_frames");
  EXPECT_TRUE(holds_only_frames(dir));  // empty
  std::ofstream(dir / frame_file_name(3)) << "x";
  std::ofstream(dir / kFolderManifestName) << "{}";
  EXPECT_TRUE(holds_only_frames(dir));
  std::ofstream(dir / "notes.txt") << "mine";
  EXPECT_FALSE(holds_only_frames(dir));
  std::filesystem::remove(dir / "notes.txt");
  std::filesystem::create_directory(dir / "frame_000009.png");  // a folder, not a frame
  EXPECT_FALSE(holds_only_frames(dir));
  EXPECT_THAT(
      [&] { holds_only_frames(dir / "missing"); },
      ThrowsMessage<InputError>(HasSubstr("cannot write PNG frames to '" +
                                          (dir / "missing").string() + "': cannot list it")));
  std::filesystem::remove_all(dir);
}

TEST(OutputKind, OutputFolders) {
  EXPECT_EQ(without_trailing_slash("frames//"), "frames");
  EXPECT_EQ(without_trailing_slash("/"), "/");
  EXPECT_EQ(output_directory("out.mp4"), ".");
  EXPECT_EQ(output_directory("a/b/out.mp4"), "a/b");
  EXPECT_THAT([] { require_output_directory("/nonexistent/dir/out.mp4"); },
              ThrowsMessage<InputError>("cannot write '/nonexistent/dir/out.mp4': directory "
                                        "'/nonexistent/dir' does not exist"));
}

}  // namespace
}  // namespace tumble::media
