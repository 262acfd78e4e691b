#pragma once
/// @file `tumble view`: the interactive viewer (SDL2 window, Dear ImGui panels, the off-screen
/// renderer's frames). The window lives in app/viewer/window/, built when the TUMBLE_VIEWER option
/// is on (the default where SDL2 is found); without it `tumble view` says so and fails.

#include <iosfwd>

#include "app/viewer/view_options.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace tumble::app {

/// Adds the `view` subcommand and its options to `cli`, filling `options` when parsed.
CLI::App& add_view_command(CLI::App& cli, ViewOptions& options);

/// Runs the viewer until its window closes. Returns 0, or 1 with one line on `err` when the
/// options are wrong, there is no display, or this build has no viewer. Scene and mesh errors
/// show in the window, which keeps running.
int run_view(const ViewOptions& options, std::ostream& out, std::ostream& err);

}  // namespace tumble::app
