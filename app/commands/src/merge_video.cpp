// Merging the parts of a sharded render or comparison: checks, then one ffmpeg run (or links).
//
// Everything is built in a staging folder beside the output (`.OUT.tmp-PID`: the concat list,
// the PNG frames linked for ffmpeg, the new video) and renamed into place at the end; a failure
// or an interruption removes the folder, so nothing is left under the output's name.
#include "merge_video.hpp"

#include <sys/stat.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "app/farm/shard.hpp"
#include "app/support/child_process.hpp"
#include "app/support/file_write.hpp"
#include "base/errors.hpp"
#include "base/file_checks.hpp"
#include "base/temporary_path.hpp"
#include "base/video_encoding.hpp"

namespace tumble::app {

namespace {

using nlohmann::json;
namespace fs = std::filesystem;

/// One part's frames [first, end), in shard order.
struct Segment {
  fs::path part;
  std::size_t first = 0;
  std::size_t end = 0;
};

/// What the parts make together.
struct VideoJob {
  std::string format;  ///< of the parts: png, mp4 or webm
  double fps = 30.0;
  std::size_t first = 0;  ///< the job's frames A:B
  std::size_t end = 0;
  std::vector<Segment> segments;
};

std::string frame_name(std::size_t index) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%06zu.png", index);
  return name;
}

std::string range_text(std::size_t first, std::size_t end) {
  return std::to_string(first) + ":" + std::to_string(end);
}

/// The format `output` asks for: png (a folder), mp4, webm or gif.
std::string output_format(const fs::path& output) {
  const std::string text = output.string();
  std::error_code error;
  if (!text.empty() && (text.back() == '/' || fs::is_directory(output, error))) return "png";
  const std::string extension = output.extension().string();
  if (extension == ".mp4" || extension == ".webm" || extension == ".gif") {
    return extension.substr(1);
  }
  throw InputError("unknown output '" + text +
                   "': expected a directory ending in '/' (PNG frames) or a .mp4, .webm or .gif "
                   "file");
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
VideoJob video_job(const std::vector<NamedManifest>& parts, const std::vector<std::size_t>& order) {
  const NamedManifest& first = parts[order.front()];
  const json& job = first.manifest.job;
  const json options = job.value("options", json::object());
  VideoJob video;
  std::tie(video.first, video.end) =
      frame_pair(options, "frames", first.part, "job.options.frames");
  const json fps = options.value("fps", json());
  if (!fps.is_number() || !(fps.get<double>() > 0.0)) {
    throw InputError(first.part.string() + ": field 'job.options.fps': expected a frame rate");
  }
  video.fps = fps.get<double>();
  const json interval = options.value("keyframe_interval", json());
  if (!interval.is_number_unsigned() || interval.get<std::size_t>() == 0) {
    throw InputError(first.part.string() +
                     ": field 'job.options.keyframe_interval': expected a whole number of frames");
  }
  video.format = job.value("output", "");
  if (video.format != "png" && video.format != "mp4" && video.format != "webm") {
    throw InputError(first.part.string() + ": field 'job.output': expected png, mp4 or webm");
  }
  for (const std::size_t index : order) {
    const NamedManifest& named = parts[index];
    const auto [begin, end] =
        frame_pair(named.manifest.payload, "frames", named.part, "payload.frames");
    const ItemRange range =
        aligned_range(video.end - video.first, interval.get<std::size_t>(), named.manifest.shard);
    if (begin != video.first + range.begin || end != video.first + range.end) {
      throw InputError(named.part.string() + ": holds frames " + range_text(begin, end) +
                       ", but shard " + named.manifest.shard.text() + " of frames " +
                       range_text(video.first, video.end) + " is frames " +
                       range_text(video.first + range.begin, video.first + range.end));
    }
    video.segments.push_back({named.part, begin, end});
  }
  return video;
}

/// Checks that a PNG part holds exactly its frames' files.
void check_png_part(const Segment& segment) {
  for (std::size_t frame = segment.first; frame < segment.end; ++frame) {
    std::error_code error;
    if (!fs::is_regular_file(segment.part / frame_name(frame), error)) {
      throw InputError(segment.part.string() + ": " + frame_name(frame) +
                       " missing (the part is frames " + range_text(segment.first, segment.end) +
                       ")");
    }
  }
  std::error_code error;
  for (fs::directory_iterator entry(segment.part, error), end; !error && entry != end;
       entry.increment(error)) {
    const std::string name = entry->path().filename().string();
    if (!name.starts_with("frame_") || !name.ends_with(".png")) continue;
    const std::string digits = name.substr(6, name.size() - 10);
    const std::size_t frame = std::strtoull(digits.c_str(), nullptr, 10);
    if (frame < segment.first || frame >= segment.end) {
      throw InputError(segment.part.string() + ": " + name + " is not one of its frames " +
                       range_text(segment.first, segment.end));
    }
  }
}

/// Checks that a video part holds as many frames as its manifest says (ffprobe counts them).
void check_video_part(const Segment& segment) {
  const ChildResult probe =
      run_child({"ffprobe", "-v", "error", "-select_streams", "v:0", "-count_packets",
                 "-show_entries", "stream=nb_read_packets", "-of",
                 "default=noprint_wrappers=1:nokey=1", segment.part.string()});
  if (probe.status != 0) {
    throw InputError(segment.part.string() +
                     ": not a readable video (ffprobe: " + last_lines(probe.err) + ")");
  }
  const std::size_t frames = std::strtoull(probe.out.c_str(), nullptr, 10);
  if (frames != segment.end - segment.first) {
    throw InputError(segment.part.string() + ": holds " + std::to_string(frames) +
                     " frames, its manifest says " + std::to_string(segment.end - segment.first) +
                     " (frames " + range_text(segment.first, segment.end) + ")");
  }
}

/// The staging folder, removed with everything in it unless it was renamed into place.
struct Staging {
  fs::path folder;
  explicit Staging(fs::path path) : folder(std::move(path)) {
    std::error_code error;
    fs::remove_all(folder, error);
    if (!fs::create_directory(folder, error)) {
      throw InputError("cannot write '" + folder.parent_path().string() +
                       "': cannot create a folder there: " + error.message());
    }
  }
  ~Staging() {
    std::error_code ignored;
    fs::remove_all(folder, ignored);
  }
  Staging(const Staging&) = delete;
  Staging& operator=(const Staging&) = delete;
};

/// Hard-links (or copies) every frame of the PNG parts into `folder`.
void link_frames(const VideoJob& video, const fs::path& folder) {
  for (const Segment& segment : video.segments) {
    for (std::size_t frame = segment.first; frame < segment.end; ++frame) {
      const fs::path from = segment.part / frame_name(frame);
      const fs::path to = folder / frame_name(frame);
      std::error_code error;
      fs::create_hard_link(from, to, error);
      if (error) fs::copy_file(from, to, error);
      if (error) {
        throw InputError("cannot write '" + to.string() + "' (from '" + from.string() +
                         "'): " + error.message());
      }
    }
  }
}

/// The concat demuxer's list of the segments, in order.
fs::path write_concat_list(const VideoJob& video, const fs::path& folder) {
  std::string list = "ffconcat version 1.0\n";
  for (const Segment& segment : video.segments) {
    std::string quoted;
    for (const char c : fs::absolute(segment.part).string()) {
      quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    }
    list += "file '" + quoted + "'\n";
  }
  const fs::path file = folder / "segments.ffconcat";
  write_text_file(file, list);
  return file;
}

/// The ffmpeg command that makes the output `result` in the staging folder.
std::vector<std::string> ffmpeg_command(const VideoJob& video, const std::string& format,
                                        const fs::path& folder, const fs::path& result) {
  std::vector<std::string> command = {"ffmpeg",    "-hide_banner", "-nostdin", "-nostats",
                                      "-loglevel", "error",        "-y"};
  if (video.format == "png") {
    link_frames(video, folder / "frames");
    command.insert(command.end(), {"-framerate", ffmpeg_rate(video.fps), "-start_number",
                                   std::to_string(video.first), "-i",
                                   (folder / "frames" / "frame_%06d.png").string()});
  } else {
    command.insert(command.end(),
                   {"-f", "concat", "-safe", "0", "-i", write_concat_list(video, folder).string()});
  }
  command.insert(command.end(), {"-map_metadata", "-1"});  // no part manifest in the whole
  if (format == video.format) {
    command.insert(command.end(), {"-c", "copy", "-f", format});
  } else if (format == "png") {
    command.insert(command.end(), {"-start_number", std::to_string(video.first), "-f", "image2"});
  } else {
    for (std::string& argument : ffmpeg_encoder_arguments(format, video.fps))
      command.push_back(argument);
  }
  command.push_back(format == "png" ? (result / "frame_%06d.png").string() : result.string());
  return command;
}

/// Whether a folder holds only PNG frames (and a part's manifest): one a merge may replace.
bool holds_only_frames(const fs::path& folder) {
  std::error_code error;
  for (fs::directory_iterator entry(folder, error), end; !error && entry != end;
       entry.increment(error)) {
    const std::string name = entry->path().filename().string();
    if (!(name.starts_with("frame_") && name.ends_with(".png")) && name != "part.json") {
      return false;
    }
  }
  return !error;
}

/// Moves the finished `result` to `destination` (a folder replaces an earlier one).
void move_into_place(const fs::path& result, const fs::path& destination, const fs::path& output,
                     bool folder) {
  std::error_code error;
  const fs::path old = temporary_sibling(destination, "old");
  const bool replacing = folder && fs::exists(destination, error);
  if (replacing) fs::rename(destination, old, error);
  if (!error) fs::rename(result, destination, error);
  if (error)
    throw InputError("cannot move the merged video into '" + output.string() +
                     "': " + error.message());
  if (replacing) fs::remove_all(old, error);
}

}  // namespace

VideoMerge merge_video_parts(const std::vector<NamedManifest>& parts, const fs::path& output,
                             const std::function<bool()>& interrupted) {
  const std::string format = output_format(output);
  const std::vector<std::size_t> order = check_parts_cover_job(parts);
  const VideoJob video = video_job(parts, order);
  for (const Segment& segment : video.segments) {
    if (video.format == "png") {
      check_png_part(segment);
    } else {
      check_video_part(segment);
    }
  }
  // The output: a new name, a regular file or a folder of frames, never one of the parts.
  std::vector<fs::path> inputs;
  for (const Segment& segment : video.segments) inputs.push_back(segment.part);
  const bool folder = format == "png";
  fs::path destination = checked_output(output, inputs, folder);
  if (!destination.has_filename()) destination = destination.parent_path();  // "out/" -> "out"
  std::error_code error;
  if (folder && fs::is_directory(destination, error) && !holds_only_frames(destination)) {
    throw InputError("refusing to replace '" + output.string() +
                     "': it holds files other than frame_*.png");
  }
  remove_stale_temporaries(destination);
  const Staging staging(temporary_sibling(destination));

  VideoMerge merge;
  merge.frames = video.end - video.first;
  merge.copied = format == video.format && format != "png";
  const fs::path result = staging.folder / (folder ? "frames-out" : "video");
  if (folder) fs::create_directory(result, error);
  fs::create_directory(staging.folder / "frames", error);
  if (folder && video.format == "png") {
    link_frames(video, result);
  } else {
    const ChildResult ffmpeg =
        run_child(ffmpeg_command(video, format, staging.folder, result), interrupted);
    if (ffmpeg.cancelled || interrupted()) {
      merge.interrupted = true;
      return merge;
    }
    if (ffmpeg.status != 0) {
      throw InputError("ffmpeg failed writing '" + output.string() + "' (exit status " +
                       std::to_string(ffmpeg.status) + "): " + last_lines(ffmpeg.err));
    }
  }
  if (interrupted()) {
    merge.interrupted = true;
    return merge;
  }
  move_into_place(result, destination, output, folder);
  return merge;
}

}  // namespace tumble::app
