#pragma once
/// @file `tumble inertials` as library calls: each link's stated inertial compared with the one
/// its geometry gives (inertials_report, returning data), that comparison as a table and as
/// JSON, and the whole command (write_inertials).

#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/robot/inertial_xml.hpp"
#include "app/robot/link_inertial.hpp"
#include "app/robot/robot_model.hpp"
#include "app/robot/robot_total.hpp"

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

/// One link: what the file states, what was computed, and how far apart they are.
struct LinkComparison {
  std::string name;
  std::size_t geometries = 0;
  std::optional<robot::StatedInertial> stated;
  robot::LinkInertial result;
  /// Why the stated values cannot be right (missing, zero mass, not positive definite,
  /// triangle inequality broken), one sentence each.
  std::vector<std::string> problems;
  /// The link's and its meshes' notes.
  std::vector<std::string> notes;
  /// Relative differences, when both sides have the value: |Δm| / m; |Δc| / r, with r the
  /// root-mean-square distance of the computed body's matter from its centre of mass
  /// (sqrt(tr I / 2m), the link's size); ||ΔI|| / ||I|| (Frobenius norms), and the same of
  /// the principal moments.
  std::optional<double> mass;
  std::optional<double> center_of_mass;
  std::optional<double> inertia;
  std::optional<double> moments;
  /// SDF <inertial auto="true">: the computed inertial is the file's by definition.
  bool auto_inertial = false;
};

/// The comparison for `link`, whose inertial came out as `result`.
LinkComparison compare_link(const robot::Link& link, robot::LinkInertial result);

/// Whether `--check` passes the link: it has no geometry (nothing to compare), or it states
/// every value, none impossible, each within `tolerance` of the computed one. A failed link
/// does not pass.
bool within_tolerance(const LinkComparison& link, double tolerance);

/// The table for people: a block per link, then the whole robot's `total` when given.
std::string format_comparison(const robot::Robot& robot, const std::vector<LinkComparison>& links,
                              const std::string& source, double tolerance, bool check,
                              const std::optional<robot::RobotTotal>& total = std::nullopt);

/// The same as data: {"file", "format", "from", "links": [...], "total": {...} or null}.
nlohmann::json comparison_to_json(const robot::Robot& robot,
                                  const std::vector<LinkComparison>& links,
                                  const std::string& source, double tolerance, bool check,
                                  const std::optional<robot::RobotTotal>& total = std::nullopt);

/// Each link's final inertial, in its frame: the computed one, else (a link without geometry)
/// the stated one when it gives a positive mass and an inertia; unset otherwise.
std::vector<std::optional<engine::MassProperties>> final_inertials(
    const std::vector<LinkComparison>& links);

/// A robot file's links compared: the robot as read and one comparison per link, in order.
struct InertialsReport {
  robot::Robot robot;
  std::vector<LinkComparison> links;
  /// "collision" or "visual": the geometry the inertials came from.
  std::string source;
  /// The whole robot in its zero configuration, from each link's final inertial; unset when
  /// no link has one.
  std::optional<robot::RobotTotal> total;
  /// Whether some link's geometry failed (LinkComparison::result.error says why).
  bool failed() const;
  /// One line per failed link, "FILE: why", as the command prints them after "error: ".
  std::vector<std::string> errors() const;
};

/// `--package-path NAME=DIR` values as package paths, in the order given. Throws InputError
/// "--package-path 'X': expected NAME=DIR" for a malformed one.
robot::PackagePaths package_paths(const std::vector<std::string>& given);

/// Reads `file` as `read` says and computes and compares every link's inertial as `compute`
/// says; nothing is printed or written. Throws InputError for a file that cannot be read.
InertialsReport compute_inertials(const std::filesystem::path& file, const robot::ReadOptions& read,
                                  const robot::ComputeOptions& compute);

/// Reads `options.robot` (its --from geometry, --package-path) and computes and compares every
/// link's inertial; nothing is printed or written. Throws InputError for a file that cannot be
/// read.
InertialsReport inertials_report(const InertialsOptions& options);

/// The robot file's text with each computed inertial in place of the stated one (every other
/// byte kept); coordinates and products of inertia within rounding of zero are written 0.
std::string rewritten_inertials(const InertialsReport& report, robot::InertialFrame frame);

/// Writes rewritten_inertials to `output` whole or not at all (a temporary sibling renamed into
/// place); never over the robot file itself. tumble::InputError when a link failed or the
/// output cannot be written.
void write_inertials(const InertialsReport& report, const std::filesystem::path& output,
                     robot::InertialFrame frame);

/// The whole `tumble inertials`: the report on `out` (table or JSON), an error line per failed
/// link on `err`, -o written atomically when no link failed. Returns kExitInputError when a link
/// failed, kExitCheckFailed when --check found a difference, else kExitDone.
int write_inertials(const InertialsOptions& options, std::ostream& out, std::ostream& err);

}  // namespace tumble::app
