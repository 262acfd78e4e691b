#pragma once
/// @file `tumble inspect`: mass properties of meshes, for people, for scripts and for robot
/// files, one mesh or a batch of thousands.

#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "app/robot/inertial_xml.hpp"
#include "engine/mass/mesh_analysis.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace tumble::app {

/// How the reports are printed: the table; one JSON document (an object, or an array for a
/// batch); JSON lines (one object per file as it finishes); an inertial element of a URDF,
/// SDF or MJCF file.
enum class InspectFormat { text, json, jsonl, urdf, sdf, mjcf };

/// What `tumble inspect` was asked to do.
struct InspectOptions {
  /// Mesh files, directories (the mesh files directly inside, or below with `recursive`) and
  /// `@LIST` files (one path a line, relative to the list's folder).
  std::vector<std::filesystem::path> files;
  engine::MassOptions mass;
  InspectFormat format = InspectFormat::text;
  /// The frame of the XML formats' inertia: the mesh file's axes or the principal axes.
  robot::InertialFrame frame = robot::InertialFrame::mesh;
  bool recursive = false;     ///< directories: descend into sub-directories
  unsigned jobs = 1;          ///< files inspected at once; 0: one per core
  bool format_given = false;  ///< --format, --json or --jsonl was given
  /// -o FILE: the output written there (atomically) instead of on stdout.
  std::optional<std::filesystem::path> output;
  /// "I/N": only every N-th file of the list from the I-th, written to -o FILE.jsonl as a part.
  std::optional<std::string> shard;
};

/// Adds the `inspect` subcommand and its options to `cli`, filling `options` when parsed.
CLI::App& add_inspect_command(CLI::App& cli, InspectOptions& options);

/// `--scale`'s value: one factor ("0.001", every axis) or three ("1,2,-1"), each finite and
/// non-zero. Throws InputError "--scale: expected one factor or three (sx,sy,sz), got ...".
Eigen::Vector3d parse_scale_factors(const std::string& text);

/// Runs the command: reports on stdout in input order, one error line per failed file on
/// stderr and, for more than one file, a summary line there. Returns the exit status (0 when
/// every file was inspected). With the json format nothing is printed unless every file
/// succeeded, so a script never reads a partial array as complete; jsonl prints each file's
/// object (or its error) as soon as it and the files before it are done.
int run_inspect(const InspectOptions& options, std::ostream& out, std::ostream& err);

}  // namespace tumble::app
