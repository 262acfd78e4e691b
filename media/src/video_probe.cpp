// ffprobe's answers about a video, one small child process each.
#include "media/video_probe.hpp"

#include <cstdlib>
#include <vector>

#include "base/errors.hpp"
#include "base/process.hpp"

namespace tumble::media {
namespace {

/// ffprobe's standard output for `arguments` then `video`, after checking it read the file.
std::string probe(std::vector<std::string> arguments, const std::filesystem::path& video) {
  arguments.insert(arguments.begin(), {"ffprobe", "-v", "error"});
  arguments.push_back(video.string());
  ProcessResult result;
  try {
    result = run_process(arguments);
  } catch (const InputError& error) {
    throw InputError(video.string() + ": cannot read it: " + error.what());
  }
  if (result.status != 0) {
    throw InputError(video.string() + ": not a readable video (ffprobe: " + last_lines(result.err) +
                     ")");
  }
  return result.out;
}

}  // namespace

std::size_t count_video_frames(const std::filesystem::path& video) {
  const std::string out =
      probe({"-select_streams", "v:0", "-count_packets", "-show_entries", "stream=nb_read_packets",
             "-of", "default=noprint_wrappers=1:nokey=1"},
            video);
  return std::strtoull(out.c_str(), nullptr, 10);
}

std::string video_comment(const std::filesystem::path& video) {
  std::string comment = probe(
      {"-show_entries", "format_tags=comment", "-of", "default=noprint_wrappers=1:nokey=1"}, video);
  while (!comment.empty() && (comment.back() == '\n' || comment.back() == '\r')) comment.pop_back();
  return comment;
}

}  // namespace tumble::media
