#pragma once
/// @file `tumble inertials`: each link's inertial of a robot description (URDF, SDF, MJCF)
/// computed from its geometry, compared with what the file states, and optionally written back
/// into a copy of the file with only the inertial elements changed.

#include <iosfwd>

#include "app/robot/inertials_report.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace tumble::app {

/// Adds the `inertials` subcommand and its options to `cli`, filling `options` when parsed.
CLI::App& add_inertials_command(CLI::App& cli, InertialsOptions& options);

/// Runs the command: the comparison on `out` (a table, or JSON), one error line per failed
/// link on `err`. Returns kExitInputError when the file or a link failed (then nothing is
/// written), kExitCheckFailed when `--check` found a difference, else kExitDone.
int run_inertials(const InertialsOptions& options, std::ostream& out, std::ostream& err);

}  // namespace tumble::app
