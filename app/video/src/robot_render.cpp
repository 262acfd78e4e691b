// `tumble render ROBOT -o robot.png`.
#include "app/video/robot_render.hpp"

#include <cctype>
#include <ostream>
#include <system_error>

#include "app/video/robot_picture.hpp"
#include "base/errors.hpp"
#include "base/file_checks.hpp"
#include "base/temporary_path.hpp"
#include "media/png_io.hpp"
#include "render/overlay_layout.hpp"

namespace tumble::app {
namespace {

using tumble::InputError;

/// Refuses the options of a video, naming the first one given.
void refuse_video_options(const RenderOptions& options) {
  const auto refuse = [](const char* option) {
    throw InputError(std::string(option) + ": a robot file renders to one still image");
  };
  if (options.fps) refuse("--fps");
  if (options.frames) refuse("--frames");
  if (options.time_scale) refuse("--time-scale");
  if (options.shard) refuse("--shard");
  if (options.integrator) refuse("--integrator");
  if (options.dt) refuse("--dt");
}

RobotPictureOptions picture_options(const RenderOptions& options) {
  RobotPictureOptions picture;
  if (options.robot_from) {
    if (*options.robot_from != "collision" && *options.robot_from != "visual") {
      throw InputError("--from: expected collision or visual, got '" + *options.robot_from + "'");
    }
    if (*options.robot_from == "visual") picture.from = robot::GeometrySource::visual;
  }
  picture.package_paths = options.package_paths;
  return picture;
}

}  // namespace

int write_robot_render(const RenderOptions& options, std::ostream& out) {
  refuse_video_options(options);
  std::string extension = options.output.extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (extension != ".png") {
    throw InputError("-o '" + options.output.string() +
                     "': a robot file renders to one .png image");
  }
  const auto [width, height] = parse_frame_size(options.size.value_or("1280x720"));
  Antialiasing antialiasing;
  if (options.antialiasing) {
    const std::optional<Antialiasing> parsed = antialiasing_from_text(*options.antialiasing);
    if (!parsed) {
      throw InputError(std::string("--aa: ") + kAntialiasingExpected + ", got " +
                       *options.antialiasing);
    }
    antialiasing = *parsed;
  }
  const double font_scale = options.font_scale ? font_scale_option(*options.font_scale) : 1.0;
  const std::filesystem::path target = checked_output(options.output, {options.scene});

  // Everything that can fail on the input comes before the renderer and the output.
  const RobotPicture picture = load_robot_picture(options.scene, picture_options(options));
  render::Renderer renderer(
      renderer_options(antialiasing, width, height, options.lod.value_or(true)));
  const RobotDrawing drawing(picture, renderer);
  const float font_px = render::overlay_font_px(width, height, font_scale);
  const Image image = renderer.render(drawing.frame(robot_camera(picture, width, height),
                                                    std::nullopt, !options.no_overlay, font_px));

  remove_stale_temporaries(target);
  const std::filesystem::path temporary = temporary_sibling(target);
  try {
    media::write_png(temporary, image);
    std::filesystem::rename(temporary, target);
  } catch (const std::exception& error) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw InputError("cannot write '" + options.output.string() + "': " + error.what());
  }
  if (!options.quiet) {
    out << "wrote " << options.output.string() << " (" << width << "x" << height
        << "): " << picture.links.size() << " links, " << picture.differing()
        << " differing from their computed inertials\n";
  }
  return 0;
}

}  // namespace tumble::app
