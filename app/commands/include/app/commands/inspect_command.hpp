#pragma once
/// @file `tumble inspect`: mass properties of meshes, for people and for scripts.

#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include "engine/mesh_analysis.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace tumble::app {

/// What `tumble inspect` was asked to do.
struct InspectOptions {
  std::vector<std::filesystem::path> files;
  engine::MassOptions mass;
  bool json = false;
};

/// Adds the `inspect` subcommand and its options to `cli`, filling `options` when parsed.
CLI::App& add_inspect_command(CLI::App& cli, InspectOptions& options);

/// Runs the command: reports on stdout, one error line per failed file on stderr. Returns the
/// exit status (0 when every file was inspected). With --json nothing is printed unless every
/// file succeeded, so a script never reads a partial array as complete.
int run_inspect(const InspectOptions& options, std::ostream& out, std::ostream& err);

}  // namespace tumble::app
