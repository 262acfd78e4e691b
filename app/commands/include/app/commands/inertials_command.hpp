#pragma once
/// @file `tumble inertials`: each link's inertial of a robot description (URDF, SDF, MJCF)
/// computed from its geometry, compared with what the file states, and optionally written back
/// into a copy of the file with only the inertial elements changed.

#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "app/robot/inertial_xml.hpp"
#include "app/robot/link_inertial.hpp"
#include "app/robot/robot_model.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace tumble::app {

/// What `tumble inertials` was asked to do.
struct InertialsOptions {
  std::filesystem::path robot;
  robot::GeometrySource from = robot::GeometrySource::collision;
  robot::ComputeOptions compute;
  /// `--package-path NAME=DIR`, in the order given (ROS_PACKAGE_PATH is looked at after them).
  std::vector<std::string> package_paths;
  robot::InertialFrame frame = robot::InertialFrame::mesh;
  bool json = false;
  /// `-o`: the rewritten file.
  std::optional<std::filesystem::path> output;
  /// `--check`: exit kExitCheckFailed when a link differs by more than `tolerance`.
  bool check = false;
  double tolerance = 1e-3;
};

/// Adds the `inertials` subcommand and its options to `cli`, filling `options` when parsed.
CLI::App& add_inertials_command(CLI::App& cli, InertialsOptions& options);

/// Runs the command: the comparison on `out` (a table, or JSON), one error line per failed
/// link on `err`. Returns kExitInputError when the file or a link failed (then nothing is
/// written), kExitCheckFailed when `--check` found a difference, else kExitDone.
int run_inertials(const InertialsOptions& options, std::ostream& out, std::ostream& err);

}  // namespace tumble::app
