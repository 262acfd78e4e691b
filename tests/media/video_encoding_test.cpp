// The encoder settings render and merge share (tumble/video_encoding.hpp): the key-frame
// interval that video shards are cut on, and what makes an MP4 segment code as the whole video.
#include "media/video_encoding.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace tumble::media {
namespace {

using ::testing::Contains;

TEST(VideoEncoding, KeyFrameIntervalIsTwoSecondsOfFrames) {
  EXPECT_EQ(keyframe_interval(30.0), 60U);
  EXPECT_EQ(keyframe_interval(29.97), 60U);  // 59.94 rounds to 60
  EXPECT_EQ(keyframe_interval(10.0), 20U);
  EXPECT_EQ(keyframe_interval(3.0), 6U);
  EXPECT_EQ(keyframe_interval(0.5), 1U);
  EXPECT_EQ(keyframe_interval(0.1), 1U);  // never 0
}

/// The value after `option` in `arguments`, or "".
std::string value_of(const std::vector<std::string>& arguments, const std::string& option) {
  for (std::size_t i = 0; i + 1 < arguments.size(); ++i) {
    if (arguments[i] == option) return arguments[i + 1];
  }
  return "";
}

TEST(VideoEncoding, Mp4CodesEachIntervalFromItsOwnFrames) {
  const std::vector<std::string> mp4 = ffmpeg_encoder_arguments("mp4", 24.0);
  EXPECT_EQ(value_of(mp4, "-c:v"), "libx264");
  EXPECT_EQ(value_of(mp4, "-qp"), "21");  // no rate control carried across intervals
  EXPECT_EQ(value_of(mp4, "-x264-params"), "keyint=48:min-keyint=48:scenecut=0:mvrange-thread=64");
  EXPECT_GE(std::stoi(value_of(mp4, "-threads")), 2);  // frame threads, whatever the machine
  EXPECT_THAT(mp4, Contains("-crf").Times(0));
}

TEST(VideoEncoding, WebmTakesTheSameKeyFramesAndGifNone) {
  const std::vector<std::string> webm = ffmpeg_encoder_arguments("webm", 24.0);
  EXPECT_EQ(value_of(webm, "-c:v"), "libvpx-vp9");
  EXPECT_EQ(value_of(webm, "-g"), "48");
  EXPECT_EQ(value_of(webm, "-keyint_min"), "48");
  const std::vector<std::string> gif = ffmpeg_encoder_arguments("gif", 24.0);
  EXPECT_EQ(value_of(gif, "-f"), "gif");
  EXPECT_EQ(value_of(gif, "-g"), "");
  EXPECT_TRUE(ffmpeg_encoder_arguments("avi", 24.0).empty());
}

}  // namespace
}  // namespace tumble::media
