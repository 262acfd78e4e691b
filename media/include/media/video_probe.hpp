#pragma once
/// @file What ffprobe says of a video file: how many frames it holds and its comment tag (where a
/// shard's segment keeps its manifest). ffprobe runs as a child process (base/process.hpp).

#include <cstddef>
#include <filesystem>
#include <string>

namespace tumble::media {

/// The frames of `video`'s first video stream, as ffprobe counts its packets. Throws
/// tumble::InputError "VIDEO: not a readable video (ffprobe: LAST LINES)", or "VIDEO: cannot read
/// it: ffprobe not found on PATH".
std::size_t count_video_frames(const std::filesystem::path& video);

/// The container's comment tag of `video` (MP4: the ilst comment atom; WebM: the Matroska COMMENT
/// tag), without its line end; "" when it has none. Throws as count_video_frames.
std::string video_comment(const std::filesystem::path& video);

}  // namespace tumble::media
