#pragma once
/// @file The one set of ffmpeg encoder settings per video format, shared by the ffmpeg sink
/// (frames piped from the renderer) and the joiner (PNG parts encoded once, media/video_join.hpp),
/// so a merged video is encoded exactly as a render to the same extension would be.
///
/// Videos are cut into key-frame intervals of a fixed length (keyframe_interval) counted from
/// the first frame, and `--shard` cuts a job only where an interval starts. For MP4 every
/// interval is then coded from its own frames alone, so segments rendered on different machines
/// and joined are the unsharded video, frame for frame (docs/merge.md):
/// - a closed GOP of exactly that length (keyint = min-keyint, scenecut=0): the key frames fall
///   at the same frames in a segment and in the whole video;
/// - a constant quantiser (-qp) instead of CRF: x264's CRF rate control carries a blurred
///   complexity over from all frames before, which a segment does not have (with CRF and the
///   same GOPs the decoded frames differed after a segment's start). QP 21 was chosen against
///   the former `-crf 23 -x264-params mbtree=0` on 240 frames of the default demo: 1.65 MB and
///   52.5 dB PSNR to the source against 1.66 MB and 52.2 dB. (The macroblock tree is off under
///   a constant quantiser.)
/// - a thread-count independent motion search: with frame threads x264 limits the vertical
///   range of motion vectors into frames still being coded to a range it derives from the
///   number of threads; mvrange-thread=64 fixes that range, and at least 2 threads keep frame
///   threading on (one thread has no such limit): measured, 2, 3, 4, 6, 12 and 16 threads code
///   the same frames alike, and 1 thread differently.
/// VP9 (WebM) takes the same key frames, but libvpx carries rate-control state across them, so
/// joined WebM segments are close to, not equal to, the whole video (docs/merge.md gives the
/// measured PSNR).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

namespace tumble::media {

/// The key-frame interval in frames at `fps`: two seconds of video, at least 1 frame.
inline std::size_t keyframe_interval(double fps) {
  const double frames = std::round(2.0 * fps);
  return frames < 1.0 ? 1 : static_cast<std::size_t>(frames);
}

/// ffmpeg's output arguments (after the input) for `format`: "mp4" (H.264), "webm" (VP9) or
/// "gif" (palette built from the stream itself); empty for anything else. `fps` sets the
/// key-frame interval of MP4 and WebM.
inline std::vector<std::string> ffmpeg_encoder_arguments(std::string_view format, double fps) {
  const std::string gop = std::to_string(keyframe_interval(fps));
  if (format == "mp4") {
    const unsigned cores = std::thread::hardware_concurrency();
    const std::string threads = std::to_string(std::max(2u, cores + cores / 2));
    return {
        "-c:v",         "libx264",
        "-preset",      "veryfast",
        "-qp",          "21",
        "-threads",     threads,
        "-x264-params", "keyint=" + gop + ":min-keyint=" + gop + ":scenecut=0:mvrange-thread=64",
        "-pix_fmt",     "yuv420p",
        "-f",           "mp4"};
  }
  if (format == "webm") {
    return {"-c:v",        "libvpx-vp9", "-deadline", "realtime", "-cpu-used", "8",   "-row-mt",
            "1",           "-b:v",       "0",         "-crf",     "32",        "-g",  gop,
            "-keyint_min", gop,          "-pix_fmt",  "yuv420p",  "-f",        "webm"};
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

}  // namespace tumble::media
