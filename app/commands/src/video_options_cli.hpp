#pragma once
/// @file The options `render` and `compare` share, as one command-line declaration.

#include <string>

#include "app/video/render_job.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace tumble::app {

/// Adds the options of VideoOptions to `command`: SCENE, -o/--output, --size (described by
/// `size_help`), --fps, --frames, --time-scale and -q/--quiet.
void add_video_options(CLI::App& command, VideoOptions& options, const std::string& size_help);

}  // namespace tumble::app
