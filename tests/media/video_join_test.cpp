// The joiner (media/video_join.hpp) against frames decoded with ffmpeg: segments cut on key frames
// and joined without re-encoding decode to the frames of the video written in one go; PNG pieces
// joined into a folder are the same files under their global numbers; failures and interruptions
// leave nothing under the output's name. And ffprobe's answers (media/video_probe.hpp).
#include "media/video_join.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "base/errors.hpp"
#include "media/image_sink.hpp"
#include "media/png_io.hpp"
#include "media/video_encoding.hpp"
#include "media/video_probe.hpp"
#include "support/run_command.hpp"
#include "support/synthetic_frames.hpp"

namespace tumble::media {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;
using tumble::testing::directory_entries;
using tumble::testing::read_text;
using tumble::testing::run_command;
namespace fs = std::filesystem;

constexpr int kJoinWidth = 64;
constexpr int kJoinHeight = 48;
constexpr double kJoinFps = 10.0;  // a key frame every 20 frames

class VideoJoin : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = tumble::testing::fresh_directory("video_join");
    frames_ = tumble::testing::turning_block_frames(kJoinWidth, kJoinHeight, 40);
  }
  void TearDown() override { fs::remove_all(dir_); }

  /// Writes frames [first, end) through a sink to `target`, as a render of that range would.
  void write(const fs::path& target, std::size_t first, std::size_t end,
             const std::string& manifest = {}) const {
    SinkOptions options;
    options.width = kJoinWidth;
    options.height = kJoinHeight;
    options.fps = kJoinFps;
    options.first_index = first;
    options.part_manifest = manifest;
    auto sink = open_image_sink(target, options);
    for (std::size_t i = first; i < end; ++i) sink->write(frames_[i]);
    sink->finish();
  }

  /// Every frame of a video as ffmpeg decodes it: raw RGBA, frame after frame.
  std::string decoded(const fs::path& video) const {
    const fs::path raw = dir_ / "decoded.rgba";
    const auto result = run_command("ffmpeg -v error -y -i '" + video.string() +
                                    "' -f rawvideo -pix_fmt rgba '" + raw.string() + "'");
    EXPECT_EQ(result.status, 0) << result.err;
    std::string bytes = read_text(raw);
    fs::remove(raw);
    return bytes;
  }

  /// Frames [first, end) of `bytes` (decoded()'s).
  static std::string decoded_frames(const std::string& bytes, std::size_t first, std::size_t end) {
    const std::size_t size = 4 * kJoinWidth * kJoinHeight;
    return bytes.substr(first * size, (end - first) * size);
  }

  fs::path dir_;
  std::vector<Image> frames_;
};

TEST_F(VideoJoin, SegmentsCutOnKeyFramesJoinIntoTheWholeVideoWithoutReEncoding) {
  ASSERT_EQ(keyframe_interval(kJoinFps), 20u);
  write(dir_ / "whole.mp4", 0, 40);
  write(dir_ / "a.mp4", 0, 20);
  write(dir_ / "b.mp4", 20, 40);
  JoinInput input{SinkKind::kMp4, kJoinFps, {{dir_ / "a.mp4", 0, 20}, {dir_ / "b.mp4", 20, 40}}};
  const JoinResult join = join_video(input, dir_ / "joined.mp4");
  EXPECT_EQ(join.frames, 40u);
  EXPECT_TRUE(join.copied);
  EXPECT_FALSE(join.interrupted);
  EXPECT_EQ(count_video_frames(dir_ / "joined.mp4"), 40u);
  const std::string whole = decoded(dir_ / "whole.mp4");
  ASSERT_EQ(whole.size(), 40u * 4 * kJoinWidth * kJoinHeight);
  EXPECT_TRUE(decoded(dir_ / "joined.mp4") == whole);  // frame for frame, bit for bit
  // Only the output is new: no staging folder or concat list is left beside it.
  EXPECT_EQ(directory_entries(dir_),
            (std::vector<std::string>{"a.mp4", "b.mp4", "joined.mp4", "whole.mp4"}));
}

TEST_F(VideoJoin, PngPiecesIntoAFolderAreTheSameFilesUnderTheirNumbers) {
  write(dir_ / "p0/", 5, 12);
  write(dir_ / "p1/", 12, 20);
  const JoinInput input{
      SinkKind::kPngSequence, kJoinFps, {{dir_ / "p0", 5, 12}, {dir_ / "p1", 12, 20}}};
  const JoinResult join = join_video(input, dir_ / "out/");
  EXPECT_EQ(join.frames, 15u);
  EXPECT_FALSE(join.copied);
  const std::vector<std::string> names = directory_entries(dir_ / "out");
  ASSERT_EQ(names.size(), 15u);
  EXPECT_EQ(names.front(), "frame_000005.png");
  EXPECT_EQ(names.back(), "frame_000019.png");
  for (std::size_t i = 5; i < 20; ++i) {
    EXPECT_EQ(read_png(dir_ / "out" / frame_file_name(i)).rgba, frames_[i].rgba) << i;
  }
  // An earlier folder of frames is replaced; a folder holding anything else is not.
  EXPECT_EQ(join_video(input, dir_ / "out/").frames, 15u);
  fs::create_directory(dir_ / "mine");
  std::ofstream(dir_ / "mine" / "notes.txt") << "keep me\n";
  EXPECT_THAT([&] { join_video(input, dir_ / "mine/"); },
              ThrowsMessage<InputError>(
                  HasSubstr("refusing to replace '" + (dir_ / "mine/").string() + "'")));
  EXPECT_EQ(read_text(dir_ / "mine" / "notes.txt"), "keep me\n");
}

TEST_F(VideoJoin, PngPiecesEncodeAsTheSinkEncodesTheSameFrames) {
  write(dir_ / "whole.mp4", 0, 30);
  write(dir_ / "p0/", 0, 13);
  write(dir_ / "p1/", 13, 30);
  const JoinInput input{
      SinkKind::kPngSequence, kJoinFps, {{dir_ / "p0", 0, 13}, {dir_ / "p1", 13, 30}}};
  const JoinResult join = join_video(input, dir_ / "joined.mp4");
  EXPECT_EQ(join.frames, 30u);
  EXPECT_FALSE(join.copied);
  EXPECT_EQ(tumble::testing::probe_video(dir_ / "joined.mp4"), "h264,64,48,30");
  EXPECT_TRUE(decoded(dir_ / "joined.mp4") == decoded(dir_ / "whole.mp4"));
}

TEST_F(VideoJoin, SegmentsIntoAFolderAreTheirDecodedFrames) {
  write(dir_ / "a.webm", 0, 20);
  write(dir_ / "b.webm", 20, 40);
  const JoinInput input{
      SinkKind::kWebm, kJoinFps, {{dir_ / "a.webm", 0, 20}, {dir_ / "b.webm", 20, 40}}};
  const JoinResult join = join_video(input, dir_ / "frames/");
  EXPECT_EQ(join.frames, 40u);
  ASSERT_EQ(directory_entries(dir_ / "frames").size(), 40u);
  const std::string second = decoded(dir_ / "b.webm");
  for (std::size_t i : {20u, 33u, 39u}) {
    const Image frame = read_png(dir_ / "frames" / frame_file_name(i));
    const std::string bytes(frame.rgba.begin(), frame.rgba.end());
    EXPECT_TRUE(bytes == decoded_frames(second, i - 20, i - 19)) << i;
  }
}

TEST_F(VideoJoin, AnInterruptedJoinLeavesNothing) {
  write(dir_ / "p0/", 0, 40);
  const JoinInput input{SinkKind::kPngSequence, kJoinFps, {{dir_ / "p0", 0, 40}}};
  const JoinResult join = join_video(input, dir_ / "out.webm", [] { return true; });
  EXPECT_TRUE(join.interrupted);
  EXPECT_EQ(directory_entries(dir_), std::vector<std::string>{"p0"});
}

TEST_F(VideoJoin, BadOutputsAndFfmpegFailuresAreOneLineAndLeaveNothing) {
  write(dir_ / "a.mp4", 0, 20);
  const JoinInput segments{SinkKind::kMp4, kJoinFps, {{dir_ / "a.mp4", 0, 20}}};
  EXPECT_THAT(
      [&] { join_video(segments, dir_ / "out.avi"); },
      ThrowsMessage<InputError>(HasSubstr("unknown output '" + (dir_ / "out.avi").string() + "'")));
  EXPECT_THAT([&] { join_video(segments, dir_ / "a.mp4"); },
              ThrowsMessage<InputError>(HasSubstr("(an input is never overwritten)")));
  std::ofstream(dir_ / "broken.mp4") << "not a video";
  const JoinInput broken{SinkKind::kMp4, kJoinFps, {{dir_ / "broken.mp4", 0, 20}}};
  EXPECT_THAT([&] { join_video(broken, dir_ / "out.mp4"); },
              ThrowsMessage<InputError>(::testing::AllOf(
                  HasSubstr("ffmpeg failed writing '" + (dir_ / "out.mp4").string() + "'"),
                  ::testing::Not(HasSubstr("\n")))));
  EXPECT_EQ(directory_entries(dir_), (std::vector<std::string>{"a.mp4", "broken.mp4"}));
}

TEST_F(VideoJoin, ProbeCountsFramesAndReadsTheCommentTag) {
  write(dir_ / "tagged.webm", 0, 20, R"({"tumble_part":1})");
  EXPECT_EQ(count_video_frames(dir_ / "tagged.webm"), 20u);
  EXPECT_EQ(video_comment(dir_ / "tagged.webm"), R"({"tumble_part":1})");
  write(dir_ / "plain.mp4", 0, 3);
  EXPECT_EQ(video_comment(dir_ / "plain.mp4"), "");
  std::ofstream(dir_ / "text.mp4") << "hello";
  EXPECT_THAT([&] { count_video_frames(dir_ / "text.mp4"); },
              ThrowsMessage<InputError>(
                  HasSubstr((dir_ / "text.mp4").string() + ": not a readable video (ffprobe: ")));
  const std::string path = std::getenv("PATH") ? std::getenv("PATH") : "";
  ::setenv("PATH", "/nonexistent", 1);
  EXPECT_THAT([&] { video_comment(dir_ / "plain.mp4"); },
              ThrowsMessage<InputError>((dir_ / "plain.mp4").string() +
                                        ": cannot read it: ffprobe not found on PATH"));
  ::setenv("PATH", path.c_str(), 1);
}

}  // namespace
}  // namespace tumble::media
