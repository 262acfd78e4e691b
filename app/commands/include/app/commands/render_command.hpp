#pragma once
/// @file `tumble render`: a scene rendered off-screen into a video or a PNG sequence (the
/// frames and their timing: app/video/render_job.hpp).

#include <iosfwd>
#include <string>

#include "app/support/exit_status.hpp"
#include "app/video/render_job.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace tumble::app {

/// Adds the `render` subcommand and its options to `cli`, filling `options` when parsed.
CLI::App& add_render_command(CLI::App& cli, RenderOptions& options);

/// Runs the command. Returns 0, 1 (input, output or ffmpeg error: one line on `err`, nothing
/// left under the output name), 3 (blow-up: the output is written to the end with the last
/// good state, one warning line on `err`) or kExitInterrupted. A progress bar goes to `err`
/// when it is the terminal's std::cerr; a summary line to `out` unless --quiet.
int run_render(const RenderOptions& options, std::ostream& out, std::ostream& err);

}  // namespace tumble::app
