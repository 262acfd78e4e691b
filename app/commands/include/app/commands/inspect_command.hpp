#pragma once
/// @file `tumble inspect`: mass properties of meshes, for people, for scripts and for robot
/// files, one mesh or a batch of thousands.

#include <iosfwd>

#include "app/inspect/inspect_options.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace tumble::app {

/// Adds the `inspect` subcommand and its options to `cli`, filling `options` when parsed.
CLI::App& add_inspect_command(CLI::App& cli, InspectOptions& options);

/// Runs the command: reports on stdout in input order, one error line per failed file on
/// stderr and, for more than one file, a summary line there. Returns the exit status (0 when
/// every file was inspected). With the json format nothing is printed unless every file
/// succeeded, so a script never reads a partial array as complete; jsonl prints each file's
/// object (or its error) as soon as it and the files before it are done.
int run_inspect(const InspectOptions& options, std::ostream& out, std::ostream& err);

}  // namespace tumble::app
