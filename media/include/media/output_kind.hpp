#pragma once
/// @file What an output name asks for, and the names of the frames of a PNG sequence: the rules
/// every writer of frames and videos follows (the sinks, the joiner), so a name means the same to
/// `tumble render` and `tumble merge`.
///   "frames/"   (trailing slash or an existing directory) -> frames/frame_000000.png, ...
///   "out.mp4"   H.264;  "out.webm"  VP9;  "out.gif"  a palette-optimised GIF
/// (the extension in any case).

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace tumble::media {

/// Kind of output, from its name.
enum class SinkKind { kPngSequence, kMp4, kWebm, kGif };

/// The kind of output a name asks for. Throws tumble::InputError "unknown output 'NAME': ..."
/// for anything else.
SinkKind sink_kind(const std::filesystem::path& target);

/// The format's short name: "png" (a folder of PNG frames), "mp4", "webm" or "gif".
std::string_view format_name(SinkKind kind);

/// The file name of frame `index` in a PNG sequence: "frame_000042.png" (six digits at least).
std::string frame_file_name(std::size_t index);

/// The same pattern as ffmpeg's image2 muxer and demuxer take it.
inline constexpr const char* kFramePattern = "frame_%06d.png";

/// The frame number of a file name frame_file_name gives ("frame_000042.png" -> 42); none for
/// any other name.
std::optional<std::size_t> frame_file_index(std::string_view name);

/// The file a PNG folder that is one part of a sharded job keeps its manifest in, beside the
/// frames.
inline constexpr const char* kFolderManifestName = "part.json";

/// Whether every entry of the folder `directory` is a frame (a regular file named
/// frame_*.png) or a part's manifest: a folder of frames that a new one may replace. Throws
/// tumble::InputError "cannot write PNG frames to 'DIR': cannot list it: ..." when it cannot
/// be listed.
bool holds_only_frames(const std::filesystem::path& directory);

/// The path without trailing slashes ("frames/" -> "frames").
std::filesystem::path without_trailing_slash(const std::filesystem::path& target);

/// The directory an output goes into ("." for a bare file name).
std::filesystem::path output_directory(const std::filesystem::path& target);

/// Checks that the output's directory exists and is a directory; throws tumble::InputError
/// "cannot write 'TARGET': directory 'DIR' does not exist" otherwise.
void require_output_directory(const std::filesystem::path& target);

}  // namespace tumble::media
