// Merging the parts of a sharded render or comparison: checks, then one ffmpeg run (or links).
//
// Everything is built in a staging folder beside the output (`.OUT.tmp-PID`: the concat list,
// the PNG frames linked for ffmpeg, the new video) and renamed into place at the end; a failure
// or an interruption removes the folder, so nothing is left under the output's name.
#include "app/video_parts/video_merge.hpp"

#include <cstring>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>

#include "app/farm/shard.hpp"
#include "base/errors.hpp"
#include "media/output_kind.hpp"
#include "media/video_join.hpp"
#include "media/video_probe.hpp"

namespace tumble::app {

namespace {

using nlohmann::json;
namespace fs = std::filesystem;

std::string range_text(std::size_t first, std::size_t end) {
  return std::to_string(first) + ":" + std::to_string(end);
}

/// A pair of whole numbers [a, b) at `key` of `object`, or an error naming the part and field.
std::pair<std::size_t, std::size_t> frame_pair(const json& object, const char* key,
                                               const fs::path& part, const std::string& field) {
  const auto found = object.find(key);
  if (found == object.end() || !found->is_array() || found->size() != 2 ||
      !(*found)[0].is_number_unsigned() || !(*found)[1].is_number_unsigned() ||
      (*found)[0].get<std::size_t>() >= (*found)[1].get<std::size_t>()) {
    throw InputError(part.string() + ": field '" + field +
                     "': expected the frames [A, B] with A < B");
  }
  return {(*found)[0].get<std::size_t>(), (*found)[1].get<std::size_t>()};
}

/// The job's frames and format from the first part, and each part's frames, checked to be its
/// shard's stretch of them (so no two overlap and none is left out).
media::JoinInput video_job(const std::vector<NamedManifest>& parts,
                           const std::vector<std::size_t>& order) {
  const NamedManifest& first = parts[order.front()];
  const json& job = first.manifest.job;
  const json options = job.value("options", json::object());
  const auto [job_first, job_end] = frame_pair(options, "frames", first.part, "job.options.frames");
  const json fps = options.value("fps", json());
  if (!fps.is_number() || !(fps.get<double>() > 0.0)) {
    throw InputError(first.part.string() + ": field 'job.options.fps': expected a frame rate");
  }
  const json interval = options.value("keyframe_interval", json());
  if (!interval.is_number_unsigned() || interval.get<std::size_t>() == 0) {
    throw InputError(first.part.string() +
                     ": field 'job.options.keyframe_interval': expected a whole number of frames");
  }
  const std::string format = job.value("output", "");
  media::JoinInput video;
  video.fps = fps.get<double>();
  if (format == "png") {
    video.format = media::SinkKind::kPngSequence;
  } else if (format == "mp4") {
    video.format = media::SinkKind::kMp4;
  } else if (format == "webm") {
    video.format = media::SinkKind::kWebm;
  } else {
    throw InputError(first.part.string() + ": field 'job.output': expected png, mp4 or webm");
  }
  for (const std::size_t index : order) {
    const NamedManifest& named = parts[index];
    const auto [begin, end] =
        frame_pair(named.manifest.payload, "frames", named.part, "payload.frames");
    const ItemRange range =
        aligned_range(job_end - job_first, interval.get<std::size_t>(), named.manifest.shard);
    if (begin != job_first + range.begin || end != job_first + range.end) {
      throw InputError(named.part.string() + ": holds frames " + range_text(begin, end) +
                       ", but shard " + named.manifest.shard.text() + " of frames " +
                       range_text(job_first, job_end) + " is frames " +
                       range_text(job_first + range.begin, job_first + range.end));
    }
    video.pieces.push_back({named.part, begin, end});
  }
  return video;
}

/// Whether `file` begins with the PNG signature and ends with the IEND chunk (its CRC
/// included): a whole file as the sinks write it, not one cut short (RFC 2083, 3.1 and 4.1.4).
bool whole_png_file(const fs::path& file) {
  static constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  static constexpr unsigned char kEnd[12] = {0,   0,   0,    0,    'I',  'E',
                                             'N', 'D', 0xAE, 0x42, 0x60, 0x82};
  std::ifstream in(file, std::ios::binary);
  char head[8] = {}, tail[12] = {};
  if (!in.read(head, sizeof head)) return false;
  in.seekg(-static_cast<std::streamoff>(sizeof tail), std::ios::end);
  if (!in.read(tail, sizeof tail)) return false;
  return std::memcmp(head, kSignature, sizeof head) == 0 &&
         std::memcmp(tail, kEnd, sizeof tail) == 0;
}

/// Checks that a PNG part holds exactly its frames' files, each a whole PNG file.
void check_png_part(const media::JoinPiece& piece) {
  for (std::size_t frame = piece.first; frame < piece.end; ++frame) {
    std::error_code error;
    const fs::path file = piece.path / media::frame_file_name(frame);
    if (!fs::is_regular_file(file, error)) {
      throw InputError(piece.path.string() + ": " + media::frame_file_name(frame) +
                       " missing (the part is frames " + range_text(piece.first, piece.end) + ")");
    }
    if (!whole_png_file(file)) {
      throw InputError(file.string() +
                       ": not a whole PNG file (cut short?); render the part of "
                       "frames " +
                       range_text(piece.first, piece.end) + " again");
    }
  }
  std::error_code error;
  for (fs::directory_iterator entry(piece.path, error), end; !error && entry != end;
       entry.increment(error)) {
    const std::string name = entry->path().filename().string();
    const std::optional<std::size_t> frame = media::frame_file_index(name);
    if (frame && (*frame < piece.first || *frame >= piece.end)) {
      throw InputError(piece.path.string() + ": " + name + " is not one of its frames " +
                       range_text(piece.first, piece.end));
    }
  }
}

/// Checks that a video part holds as many frames as its manifest says (ffprobe counts them).
void check_video_part(const media::JoinPiece& piece) {
  const std::size_t frames = media::count_video_frames(piece.path);
  if (frames != piece.end - piece.first) {
    throw InputError(piece.path.string() + ": holds " + std::to_string(frames) +
                     " frames, its manifest says " + std::to_string(piece.end - piece.first) +
                     " (frames " + range_text(piece.first, piece.end) + ")");
  }
}

}  // namespace

VideoMerge merge_video_parts(const std::vector<NamedManifest>& parts, const fs::path& output,
                             const std::function<bool()>& interrupted) {
  media::sink_kind(output);  // an unknown output fails first
  const std::vector<std::size_t> order = check_parts_cover_job(parts);
  const media::JoinInput video = video_job(parts, order);
  for (const media::JoinPiece& piece : video.pieces) {
    if (video.format == media::SinkKind::kPngSequence) {
      check_png_part(piece);
    } else {
      check_video_part(piece);
    }
  }
  const media::JoinResult join = media::join_video(video, output, interrupted);
  return {join.frames, join.copied, join.interrupted};
}

namespace {

/// The render or compare part kind: frames (PNG folders) or segments joined into the video.
class VideoPartKind : public PartKind {
 public:
  explicit VideoPartKind(const char* name) : name_(name) {}

  std::string name() const override { return name_; }

  void check(const NamedManifest& part) const override { check_video_part_alone(part); }

  MergeOutcome merge(const std::vector<NamedManifest>& parts, const fs::path& output,
                     const std::function<bool()>& interrupted) const override {
    const VideoMerge merge = merge_video_parts(parts, output, interrupted);
    if (merge.interrupted) return {true, ""};
    std::ostringstream summary;
    summary << "tumble merge: " << parts.size() << (parts.size() == 1 ? " part, " : " parts, ")
            << merge.frames << (merge.frames == 1 ? " frame" : " frames") << " written to '"
            << output.string() << "'" << (merge.copied ? " (joined without re-encoding)" : "")
            << "\n";
    return {false, summary.str()};
  }

 private:
  const char* name_;
};

}  // namespace

void check_video_part_alone(const NamedManifest& part) {
  const media::JoinInput video = video_job({part}, {0});
  for (const media::JoinPiece& piece : video.pieces) {
    if (video.format == media::SinkKind::kPngSequence) {
      check_png_part(piece);
    } else {
      check_video_part(piece);
    }
  }
}

const PartKind& render_parts() {
  static const VideoPartKind kind("render");
  return kind;
}

const PartKind& compare_parts() {
  static const VideoPartKind kind("compare");
  return kind;
}

}  // namespace tumble::app
