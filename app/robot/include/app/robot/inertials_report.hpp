#pragma once
/// @file `tumble inertials`' comparison of each link's stated inertial with the one its
/// geometry gives, that comparison as a table and as JSON, and the file rewritten with the
/// computed inertials (the command and the Python module's tumble.inertials).

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/robot/inertial_xml.hpp"
#include "app/robot/link_inertial.hpp"
#include "app/robot/robot_model.hpp"

namespace tumble::app {

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
};

/// The comparison for `link`, whose inertial came out as `result`.
LinkComparison compare_link(const robot::Link& link, robot::LinkInertial result);

/// Whether `--check` passes the link: it has no geometry (nothing to compare), or it states
/// every value, none impossible, each within `tolerance` of the computed one. A failed link
/// does not pass.
bool within_tolerance(const LinkComparison& link, double tolerance);

/// The table for people: a block per link.
std::string format_comparison(const robot::Robot& robot, const std::vector<LinkComparison>& links,
                              const std::string& source, double tolerance, bool check);

/// The same as data: {"file", "format", "from", "links": [...]}.
nlohmann::json comparison_to_json(const robot::Robot& robot,
                                  const std::vector<LinkComparison>& links,
                                  const std::string& source, double tolerance, bool check);

/// A robot file's links, each computed and compared.
struct InertialsReport {
  robot::Robot robot;
  std::vector<LinkComparison> links;
  std::string source;  ///< "collision" or "visual": the geometry the links were computed from
  /// One line per link whose geometry failed, "FILE: LINK...: WHY" (then nothing may be written).
  std::vector<std::string> errors() const;
};

/// Reads `file` and computes every link's inertial (tumble::InputError for a bad file; a link
/// whose geometry fails is in the report, with its error).
InertialsReport compute_inertials(const std::filesystem::path& file, const robot::ReadOptions& read,
                                  const robot::ComputeOptions& compute);

/// The robot file's text with each computed inertial in place of the stated one (every other
/// byte kept); coordinates and products of inertia within rounding of zero are written 0.
std::string rewritten_inertials(const InertialsReport& report, robot::InertialFrame frame);

/// Writes rewritten_inertials to `output` whole or not at all (a temporary sibling renamed into
/// place); never over the robot file itself. tumble::InputError when a link failed or the
/// output cannot be written.
void write_inertials(const InertialsReport& report, const std::filesystem::path& output,
                     robot::InertialFrame frame);

}  // namespace tumble::app
