#pragma once
/// @file `tumble render ROBOT -o robot.png`: a robot file as one still image (robot_picture.hpp),
/// the camera framing the whole robot.

#include <iosfwd>

#include "app/video/render_job.hpp"

namespace tumble::app {

/// Renders the robot file `options.scene` into the PNG `options.output` (written whole or not
/// at all, never over an input), at --size (default 1280x720), anti-aliased as --aa says, with
/// the legend unless --no-overlay; prints "wrote FILE (WxH): N links, K differing" on `out`
/// unless --quiet. Options that only make sense for a video (--fps, --frames, --time-scale,
/// --shard, --integrator, --dt) are refused. Throws InputError (bad options, the robot file, a
/// missing mesh, the output) or std::runtime_error (no GL context). Returns 0.
int write_robot_render(const RenderOptions& options, std::ostream& out);

}  // namespace tumble::app
