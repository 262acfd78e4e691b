// The joiner: one ffmpeg run (or hard links) in a staging folder beside the output, renamed into
// place at the end.
//
// The staging folder (`.OUT.tmp-PID`) holds the concat list, the PNG frames linked for ffmpeg
// and the new video or frames; it is removed with everything in it however the join ends, so
// nothing is left under the output's name but the finished output.
#include "media/video_join.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>

#include "base/errors.hpp"
#include "base/file_checks.hpp"
#include "base/process.hpp"
#include "base/temporary_path.hpp"
#include "media/video_encoding.hpp"

namespace tumble::media {
namespace {

namespace fs = std::filesystem;

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

/// Hard-links (or copies) every frame of the PNG pieces into `folder`.
void link_frames(const JoinInput& input, const fs::path& folder) {
  for (const JoinPiece& piece : input.pieces) {
    for (std::size_t frame = piece.first; frame < piece.end; ++frame) {
      const fs::path from = piece.path / frame_file_name(frame);
      const fs::path to = folder / frame_file_name(frame);
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

/// Writes `text` to `file` whole, or throws InputError naming it.
void write_whole(const fs::path& file, const std::string& text) {
  std::FILE* out = std::fopen(file.c_str(), "wb");
  bool good = out != nullptr && std::fwrite(text.data(), 1, text.size(), out) == text.size();
  const int error = errno;
  if (out != nullptr && std::fclose(out) != 0) good = false;
  if (!good) {
    throw InputError("cannot write '" + file.string() +
                     "': " + std::strerror(error != 0 ? error : errno));
  }
}

/// The concat demuxer's list of the segments, in order.
fs::path write_concat_list(const JoinInput& input, const fs::path& folder) {
  std::string list = "ffconcat version 1.0\n";
  for (const JoinPiece& piece : input.pieces) {
    std::string quoted;
    for (const char c : fs::absolute(piece.path).string()) {
      quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    }
    list += "file '" + quoted + "'\n";
  }
  const fs::path file = folder / "segments.ffconcat";
  write_whole(file, list);
  return file;
}

/// The ffmpeg command that makes the output `result` of kind `kind` in the staging folder.
std::vector<std::string> ffmpeg_command(const JoinInput& input, SinkKind kind,
                                        const fs::path& folder, const fs::path& result) {
  const std::string first = std::to_string(input.pieces.front().first);
  std::vector<std::string> command = {"ffmpeg",    "-hide_banner", "-nostdin", "-nostats",
                                      "-loglevel", "error",        "-y"};
  if (input.format == SinkKind::kPngSequence) {
    link_frames(input, folder / "frames");
    command.insert(command.end(), {"-framerate", ffmpeg_rate(input.fps), "-start_number", first,
                                   "-i", (folder / "frames" / kFramePattern).string()});
  } else {
    command.insert(command.end(),
                   {"-f", "concat", "-safe", "0", "-i", write_concat_list(input, folder).string()});
  }
  command.insert(command.end(), {"-map_metadata", "-1"});  // no piece's tags in the whole
  const std::string format(format_name(kind));
  if (kind == input.format) {
    command.insert(command.end(), {"-c", "copy", "-f", format});
  } else if (kind == SinkKind::kPngSequence) {
    command.insert(command.end(), {"-start_number", first, "-f", "image2"});
  } else {
    for (std::string& argument : ffmpeg_encoder_arguments(format, input.fps)) {
      command.push_back(argument);
    }
  }
  command.push_back(kind == SinkKind::kPngSequence ? (result / kFramePattern).string()
                                                   : result.string());
  return command;
}

/// Moves the finished `result` to `destination` (a folder replaces an earlier one).
void move_into_place(const fs::path& result, const fs::path& destination, const fs::path& output,
                     bool folder) {
  std::error_code error;
  const fs::path old = temporary_sibling(destination, "old");
  const bool replacing = folder && fs::exists(destination, error);
  if (replacing) fs::rename(destination, old, error);
  if (!error) fs::rename(result, destination, error);
  if (error) {
    throw InputError("cannot move the merged video into '" + output.string() +
                     "': " + error.message());
  }
  if (replacing) fs::remove_all(old, error);
}

/// Where the output goes: a new name, a regular file or a folder of frames, never a piece.
fs::path checked_destination(const JoinInput& input, const fs::path& output, bool folder) {
  std::vector<fs::path> pieces;
  for (const JoinPiece& piece : input.pieces) pieces.push_back(piece.path);
  fs::path destination = checked_output(output, pieces, folder);
  if (!destination.has_filename()) destination = destination.parent_path();  // "out/" -> "out"
  std::error_code error;
  if (folder && fs::is_directory(destination, error) && !holds_only_frames(destination)) {
    throw InputError("refusing to replace '" + output.string() +
                     "': it holds files other than frame_*.png");
  }
  return destination;
}

}  // namespace

JoinResult join_video(const JoinInput& input, const fs::path& output,
                      const std::function<bool()>& interrupted) {
  const SinkKind kind = sink_kind(output);
  const auto stop = [&] { return interrupted && interrupted(); };
  JoinResult join;
  if (input.pieces.empty()) throw InputError("nothing to join into '" + output.string() + "'");
  join.frames = input.pieces.back().end - input.pieces.front().first;
  join.copied = kind == input.format && kind != SinkKind::kPngSequence;
  const bool folder = kind == SinkKind::kPngSequence;
  const fs::path destination = checked_destination(input, output, folder);
  remove_stale_temporaries(destination);
  const Staging staging(temporary_sibling(destination));
  const fs::path result = staging.folder / (folder ? "frames-out" : "video");
  std::error_code error;
  if (folder) fs::create_directory(result, error);
  fs::create_directory(staging.folder / "frames", error);
  if (folder && input.format == SinkKind::kPngSequence) {
    link_frames(input, result);
  } else {
    const ProcessResult ffmpeg =
        run_process(ffmpeg_command(input, kind, staging.folder, result), stop);
    if (ffmpeg.cancelled || stop()) {
      join.interrupted = true;
      return join;
    }
    if (ffmpeg.status != 0) {
      throw InputError("ffmpeg failed writing '" + output.string() + "' (exit status " +
                       std::to_string(ffmpeg.status) + "): " + last_lines(ffmpeg.err));
    }
  }
  if (stop()) {
    join.interrupted = true;
    return join;
  }
  move_into_place(result, destination, output, folder);
  return join;
}

}  // namespace tumble::media
