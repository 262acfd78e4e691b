// Output names: their kind, the frames' file names, and the folders frames go into.
#include "media/output_kind.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdio>
#include <system_error>

#include "base/errors.hpp"

namespace tumble::media {

SinkKind sink_kind(const std::filesystem::path& target) {
  const std::string text = target.string();
  std::error_code error;
  if (!text.empty() && (text.back() == '/' || std::filesystem::is_directory(target, error))) {
    return SinkKind::kPngSequence;
  }
  std::string extension = target.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == ".mp4") return SinkKind::kMp4;
  if (extension == ".webm") return SinkKind::kWebm;
  if (extension == ".gif") return SinkKind::kGif;
  throw InputError("unknown output '" + text +
                   "': expected a directory ending in '/' (PNG frames) or a .mp4, .webm or .gif "
                   "file");
}

std::string_view format_name(SinkKind kind) {
  switch (kind) {
    case SinkKind::kPngSequence:
      return "png";
    case SinkKind::kMp4:
      return "mp4";
    case SinkKind::kWebm:
      return "webm";
    case SinkKind::kGif:
      break;
  }
  return "gif";
}

std::string frame_file_name(std::size_t index) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%06zu.png", index);
  return name;
}

std::optional<std::size_t> frame_file_index(std::string_view name) {
  constexpr std::string_view kPrefix = "frame_";
  constexpr std::string_view kSuffix = ".png";
  if (!name.starts_with(kPrefix) || !name.ends_with(kSuffix)) return std::nullopt;
  const std::string_view digits =
      name.substr(kPrefix.size(), name.size() - kPrefix.size() - kSuffix.size());
  std::size_t index = 0;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), index);
  if (digits.size() < 6 || error != std::errc() || end != digits.data() + digits.size()) {
    return std::nullopt;
  }
  return index;
}

bool holds_only_frames(const std::filesystem::path& directory) {
  std::error_code error;
  std::filesystem::directory_iterator entry(directory, error);
  for (; !error && entry != std::filesystem::directory_iterator(); entry.increment(error)) {
    const std::string name = entry->path().filename().string();
    std::error_code type_error;
    if (!entry->is_regular_file(type_error) ||
        ((!name.starts_with("frame_") || !name.ends_with(".png")) && name != kFolderManifestName)) {
      return false;
    }
  }
  if (error) {
    throw InputError("cannot write PNG frames to '" + directory.string() +
                     "': cannot list it: " + error.message());
  }
  return true;
}

std::filesystem::path without_trailing_slash(const std::filesystem::path& target) {
  std::string text = target.string();
  while (text.size() > 1 && text.back() == '/') text.pop_back();
  return text;
}

std::filesystem::path output_directory(const std::filesystem::path& target) {
  const std::filesystem::path parent = target.parent_path();
  return parent.empty() ? std::filesystem::path(".") : parent;
}

void require_output_directory(const std::filesystem::path& target) {
  const std::filesystem::path directory = output_directory(target);
  std::error_code error;
  if (!std::filesystem::is_directory(directory, error)) {
    throw InputError("cannot write '" + target.string() + "': directory '" + directory.string() +
                     "' does not exist");
  }
}

}  // namespace tumble::media
