#pragma once
// What the engine tests compare: a farmed output against the same command run on one machine.
// A video's decoded frames (ffmpeg to raw RGB; PSNR computed here), a bench's rows apart from
// their timings, PNG frames byte for byte.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "support/csv_reader.hpp"
#include "support/run_command.hpp"

namespace tumble::testing {

/// The demo scene of the engine tests, small and short: 320x180, 81 frames.
inline std::string demo_scene() {
  return std::string(TUMBLE_SOURCE_DIR) + "/assets/scenes/t_handle_flip.json";
}
inline const char* kDemoRenderOptions = "--size 320x180 --fps 10 --time-scale 2.5 -q";
/// A bench of the demo: 3 integrators x 5 steps, one timed run each.
inline const char* kDemoBenchOptions = "--duration 1 --integrators rk4,splitting,dopri --repeat 1";

/// Why the sharded commands cannot run in this build, or "" (`--shard` and `tumble merge` are
/// issue 16's, written beside tumble farm).
inline std::string sharding_missing() {
  const std::string tumble = tumble_executable();
  if (run_command(tumble + " merge --help").status != 0) return "tumble merge is not built";
  for (const char* command : {"render", "bench"}) {
    if (run_command(tumble + " " + command + " --help").out.find("--shard") == std::string::npos) {
      return std::string("tumble ") + command + " has no --shard";
    }
  }
  return "";
}

struct DecodedVideo {
  int width = 0;
  int height = 0;
  std::vector<std::vector<unsigned char>> frames;  ///< RGB, 3 bytes a pixel
};

/// Every frame of `video`, decoded by ffmpeg.
inline DecodedVideo decode_video(const std::filesystem::path& video) {
  DecodedVideo decoded;
  const std::filesystem::path probed = video.parent_path() / "probed-input";
  std::filesystem::remove(probed);
  std::filesystem::create_symlink(video, probed);
  const std::string probe = probe_video(probed);  // codec,width,height,frames
  std::filesystem::remove(probed);
  const std::size_t first = probe.find(',');
  const std::size_t second = probe.find(',', first + 1);
  decoded.width = std::stoi(probe.substr(first + 1));
  decoded.height = std::stoi(probe.substr(second + 1));
  const std::filesystem::path raw = video.parent_path() / "decoded.rgb";
  const std::filesystem::path input = video.parent_path() / "decoded-input";
  std::filesystem::remove(input);
  std::filesystem::create_symlink(video, input);  // a name the shell line needs no quoting for
  const auto result = run_command(
      "ffmpeg -v error -y -f " + std::string(video.extension() == ".webm" ? "webm" : "mp4") +
      " -i '" + input.string() + "' -f rawvideo -pix_fmt rgb24 '" + raw.string() + "'");
  std::filesystem::remove(input);
  EXPECT_EQ(result.status, 0) << result.err;
  const std::string bytes = read_text(raw);
  std::filesystem::remove(raw);
  const std::size_t size = static_cast<std::size_t>(decoded.width) * decoded.height * 3;
  for (std::size_t at = 0; size > 0 && at + size <= bytes.size(); at += size) {
    decoded.frames.emplace_back(bytes.begin() + static_cast<std::ptrdiff_t>(at),
                                bytes.begin() + static_cast<std::ptrdiff_t>(at + size));
  }
  return decoded;
}

/// Peak signal-to-noise ratio of two RGB frames of one size, in dB (infinite when equal).
inline double psnr(const std::vector<unsigned char>& a, const std::vector<unsigned char>& b) {
  double squares = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double d = static_cast<double>(a[i]) - static_cast<double>(b[i]);
    squares += d * d;
  }
  if (squares == 0.0) return std::numeric_limits<double>::infinity();
  const double mse = squares / static_cast<double>(a.size());
  return 10.0 * std::log10(255.0 * 255.0 / mse);
}

/// The farmed video has the local one's frames. The issue asks for each within PSNR 45 dB of
/// it; MP4 segments start on the whole video's key frames and are coded from their own frames
/// alone (tumble/video_encoding.hpp), so every decoded frame is the local one exactly.
inline void expect_same_video(const std::filesystem::path& farmed,
                              const std::filesystem::path& local) {
  const DecodedVideo a = decode_video(farmed);
  const DecodedVideo b = decode_video(local);
  ASSERT_EQ(a.width, b.width);
  ASSERT_EQ(a.height, b.height);
  ASSERT_EQ(a.frames.size(), b.frames.size());
  ASSERT_GT(a.frames.size(), 10u);
  for (std::size_t i = 0; i < a.frames.size(); ++i) {
    EXPECT_TRUE(a.frames[i] == b.frames[i])
        << "frame " << i << ": PSNR " << psnr(a.frames[i], b.frames[i]) << " dB";
  }
  EXPECT_LT(psnr(a.frames.front(), b.frames.back()), 35.0) << "the frames do change";
}

/// The rows of a bench's results.csv, timing columns (seconds_*, ns_per_step) blanked.
inline std::vector<std::vector<std::string>> rows_without_timings(
    const std::filesystem::path& csv) {
  std::vector<std::vector<std::string>> rows = parse_csv_records(read_text(csv));
  if (rows.empty()) return rows;
  const std::vector<std::string> header = rows.front();
  for (std::size_t r = 1; r < rows.size(); ++r) {
    for (std::size_t c = 0; c < header.size() && c < rows[r].size(); ++c) {
      if (header[c].rfind("seconds_", 0) == 0 || header[c] == "ns_per_step") rows[r][c] = "";
    }
  }
  return rows;
}

inline void expect_same_bench(const std::filesystem::path& farmed,
                              const std::filesystem::path& local) {
  const auto a = rows_without_timings(farmed / "results.csv");
  const auto b = rows_without_timings(local / "results.csv");
  ASSERT_EQ(b.size(), 16u) << "header and 15 runs";
  EXPECT_EQ(a, b);
  EXPECT_TRUE(std::filesystem::exists(farmed / "report.md"));
}

}  // namespace tumble::testing
