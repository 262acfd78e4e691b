#pragma once
/// @file `tumble inspect`: mass properties of meshes, for people and for scripts.

#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

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

/// Imports and analyses one mesh file (throws engine::InputError naming the file). With
/// `imported`, also hands back the mesh as read (file axes, before the analysis welds, drops
/// or flips anything), for drawing it without reading the file again.
engine::MeshReport inspect_file(const std::filesystem::path& file, const engine::MassOptions& mass,
                                engine::TriangleMesh* imported = nullptr);

/// The report as one JSON object (SI units; inertia about the centre of mass, file axes).
nlohmann::json report_to_json(const engine::MeshReport& report);

/// The report as a readable table.
std::string format_report(const engine::MeshReport& report);

/// Runs the command: reports on stdout, one error line per failed file on stderr. Returns the
/// exit status (0 when every file was inspected). With --json nothing is printed unless every
/// file succeeded, so a script never reads a partial array as complete.
int run_inspect(const InspectOptions& options, std::ostream& out, std::ostream& err);

}  // namespace tumble::app
