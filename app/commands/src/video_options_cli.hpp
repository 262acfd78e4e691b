#pragma once
/// @file The options `render` and `compare` share, as one command-line declaration.

#include <optional>
#include <string>

#include "app/video/render_job.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace tumble::app {

/// Adds --font-scale F, stored in `font_scale` (render, compare and view; checked later by
/// font_scale_option).
void add_font_scale_option(CLI::App& command, std::optional<double>& font_scale);

/// Adds the options of VideoOptions to `command`: SCENE, -o/--output, --size (described by
/// `size_help`), --fps, --frames, --time-scale and -q/--quiet.
void add_video_options(CLI::App& command, VideoOptions& options, const std::string& size_help);

}  // namespace tumble::app
