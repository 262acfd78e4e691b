#include "video_options_cli.hpp"

#include <CLI/CLI.hpp>

namespace tumble::app {

void add_font_scale_option(CLI::App& command, std::optional<double>& font_scale) {
  command
      .add_option_function<double>(
          "--font-scale", [&](double value) { font_scale = value; },
          "Overlay text size F times the frame's own (default 1: 13 px at 1280x720, proportional "
          "to the frame, never under 10 px; 0.25 to 8)")
      ->type_name("F");
}

void add_video_options(CLI::App& command, VideoOptions& options, const std::string& size_help) {
  command
      .add_option_function<std::string>(
          "SCENE", [&](const std::string& value) { options.scene = value; }, "Scene file (JSON)")
      ->required()
      ->type_name("FILE");
  command
      .add_option_function<std::string>(
          "-o,--output", [&](const std::string& value) { options.output = value; },
          "A .mp4 (H.264), .webm (VP9) or .gif file, or a directory ending in '/' for "
          "frame_000000.png, ...")
      ->required()
      ->type_name("OUTPUT");
  command
      .add_option_function<std::string>(
          "--size", [&](const std::string& value) { options.size = value; }, size_help)
      ->type_name("WxH");
  command
      .add_option_function<double>(
          "--fps", [&](double value) { options.fps = value; },
          "Video frames per second N (default 30)")
      ->type_name("N");
  command
      .add_option_function<std::string>(
          "--frames", [&](const std::string& value) { options.frames = value; },
          "Render only frames A:B, half-open (A to B-1, counted from 0; A: and :B allowed); they "
          "equal the same frames of a full render, and PNG files keep their frame numbers")
      ->type_name("A:B");
  command
      .add_option_function<double>(
          "--time-scale", [&](double value) { options.time_scale = value; },
          "Simulated seconds per second of video S (default 1; 0.5 is slow motion)")
      ->type_name("S");
  add_font_scale_option(command, options.font_scale);
  command
      .add_option_function<std::string>(
          "--lod",
          [&](const std::string& value) {
            if (value != "on" && value != "off") {
              throw CLI::ValidationError("--lod", "expected on or off, got '" + value + "'");
            }
            options.lod = value == "on";
          },
          "on (the default): meshes of more than 20,000 triangles are drawn from simplified "
          "copies whose outline is under a pixel off; off: always the full mesh")
      ->type_name("on|off");
  command
      .add_option_function<std::string>(
          "--shard", [&](const std::string& value) { options.shard = value; },
          "Render only the I-th of N contiguous parts of the frames (of --frames A:B if given; "
          "I from 0) into a part that tumble merge joins: a PNG folder with part.json, or a "
          ".mp4/.webm segment with its manifest inside, starting on one of the whole video's "
          "key frames (one every 2 s)")
      ->type_name("I/N");
  command.add_flag("-q,--quiet", options.quiet,
                   "No progress bar and no summary line (warnings and errors still print)");
}

}  // namespace tumble::app
