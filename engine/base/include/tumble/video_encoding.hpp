#pragma once
/// @file The one set of ffmpeg encoder settings per video format, shared by render's ffmpeg
/// sink (frames piped from the renderer) and `tumble merge` (PNG parts encoded once), so a
/// merged video is encoded exactly as a render to the same extension would be.

#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

namespace tumble {

/// ffmpeg's output arguments (after the input) for `format`: "mp4" (H.264), "webm" (VP9) or
/// "gif" (palette built from the stream itself); empty for anything else.
inline std::vector<std::string> ffmpeg_encoder_arguments(std::string_view format) {
  if (format == "mp4") {
    return {"-c:v",     "libx264",  "-preset", "veryfast", "-x264-params",
            "mbtree=0", "-pix_fmt", "yuv420p", "-f",       "mp4"};
  }
  if (format == "webm") {
    return {"-c:v",     "libvpx-vp9", "-deadline", "realtime", "-cpu-used", "8",
            "-row-mt",  "1",          "-b:v",      "0",        "-crf",      "32",
            "-pix_fmt", "yuv420p",    "-f",        "webm"};
  }
  if (format == "gif") {
    // One pass: split the stream, build a palette from one copy and apply it to the other.
    return {"-filter_complex",
            "[0:v]split[a][b];[a]palettegen=stats_mode=diff[p];[b][p]paletteuse=dither=bayer:"
            "bayer_scale=4",
            "-loop",
            "0",
            "-f",
            "gif"};
  }
  return {};
}

/// A frame rate as ffmpeg is given it ("30", "29.97"): the same text wherever a video is made.
inline std::string ffmpeg_rate(double fps) {
  char rate[64];
  std::snprintf(rate, sizeof rate, "%.6g", fps);
  return rate;
}

}  // namespace tumble
