// `tumble inertials`.
#include "app/commands/inertials_command.hpp"

#include <cmath>
#include <filesystem>
#include <ostream>

#include <CLI/CLI.hpp>

#include "app/commands/exit_status.hpp"
#include "app/robot/rewrite.hpp"
#include "app/support/file_write.hpp"
#include "base/errors.hpp"
#include "base/file_checks.hpp"
#include "base/temporary_path.hpp"
#include "inertials_report.hpp"

namespace tumble::app {

CLI::App& add_inertials_command(CLI::App& cli, InertialsOptions& options) {
  CLI::App& command = *cli.add_subcommand(
      "inertials",
      "Each link's inertial of a robot description (URDF, SDF, MJCF) from its geometry, "
      "compared with the one the file states; -o writes a copy with them replaced");
  command.footer(
      "Exit status: 0 done; 1 bad input (the file, an option, or a link whose geometry failed: "
      "then nothing is written); 4 --check found a link differing by more than the tolerance.");
  command.add_option("ROBOT", options.robot, "Robot file: .urdf, .sdf/.world, MJCF .xml")
      ->required();
  command
      .add_option_function<std::string>(
          "--from",
          [&](const std::string& value) {
            options.from = value == "visual" ? robot::GeometrySource::visual
                                             : robot::GeometrySource::collision;
          },
          "Which geometry gives a link's shape (default collision)")
      ->check(CLI::IsMember({"collision", "visual"}))
      ->option_text("collision|visual");
  command
      .add_option_function<double>(
          "--density", [&](double value) { options.compute.density = value; },
          "kg/m^3 for every link: the masses follow from the volumes (default: keep each "
          "link's stated mass; 1000 for a link stating none)")
      ->check(CLI::PositiveNumber);
  command
      .add_option("--package-path", options.package_paths,
                  "Where package://NAME/ (and SDF model://NAME/) lead; repeatable, "
                  "looked at before ROS_PACKAGE_PATH")
      ->allow_extra_args(false)  // one NAME=DIR each time: ROBOT may follow
      ->option_text("NAME=DIR");
  command
      .add_option_function<std::string>(
          "--frame",
          [&](const std::string& value) {
            options.frame =
                value == "principal" ? robot::InertialFrame::principal : robot::InertialFrame::mesh;
          },
          "How -o writes the inertia: mesh (the link's axes, all six elements; default) or "
          "principal (the principal axes' rotation and three moments)")
      ->check(CLI::IsMember({"mesh", "principal"}))
      ->option_text("mesh|principal");
  command.add_flag("--allow-overlap", options.compute.allow_overlap,
                   "Accept meshes whose parts overlap (as inspect --allow-overlap)");
  command.add_flag("--json", options.json, "Print the comparison as JSON");
  command.add_option("-o,--output", options.output,
                     "Write the robot file with each computed inertial in place of the stated "
                     "one (every other byte kept); never the input itself");
  command.add_flag("--check", options.check,
                   "Exit 4 when a link's stated mass, centre of mass or inertia differs from "
                   "the computed one by more than the tolerance");
  command
      .add_option("--tolerance", options.tolerance,
                  "Relative difference --check accepts (default 1e-3): of the mass, of the "
                  "centre of mass to the link's size, of the inertia tensor's norm")
      ->check(CLI::NonNegativeNumber);
  return command;
}

namespace {

robot::PackagePaths package_paths(const std::vector<std::string>& given) {
  robot::PackagePaths out;
  for (const std::string& entry : given) {
    const std::size_t equals = entry.find('=');
    if (equals == std::string::npos || equals == 0 || equals + 1 == entry.size()) {
      throw InputError("--package-path '" + entry + "': expected NAME=DIR");
    }
    out.emplace_back(entry.substr(0, equals), entry.substr(equals + 1));
  }
  return out;
}

/// `properties` as -o writes them: a centre-of-mass coordinate or product of inertia within
/// rounding of zero (1e-12 of the link's size or inertia: what summing a mesh's triangles
/// leaves of an exact zero) is written 0, not 9.5e-21.
engine::MassProperties written_inertial(engine::MassProperties properties) {
  const double size = std::sqrt(properties.inertia.trace() / (2.0 * properties.mass));
  for (int i = 0; i < 3; ++i) {
    if (std::abs(properties.center_of_mass[i]) <= 1e-12 * size) properties.center_of_mass[i] = 0;
  }
  const double scale = properties.inertia.norm();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (i != j && std::abs(properties.inertia(i, j)) <= 1e-12 * scale) {
        properties.inertia(i, j) = 0;
      }
    }
  }
  return properties;
}

/// Writes `text` to `output` whole or not at all: a temporary sibling renamed into place.
void write_atomically(const std::filesystem::path& output, const std::filesystem::path& input,
                      const std::string& text) {
  const std::filesystem::path target = checked_output(output, {input});
  remove_stale_temporaries(target);
  const std::filesystem::path temporary = temporary_sibling(target);
  try {
    write_text_file(temporary, text);
    std::filesystem::rename(temporary, target);
  } catch (const std::filesystem::filesystem_error& error) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw InputError("cannot write '" + output.string() + "': " + error.code().message());
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw;
  }
}

int inertials(const InertialsOptions& options, std::ostream& out, std::ostream& err) {
  robot::ReadOptions read;
  read.from = options.from;
  read.packages = package_paths(options.package_paths);
  // A refused output fails before any work (and checked again when written).
  if (options.output) checked_output(*options.output, {options.robot});
  const robot::Robot robot = robot::read_robot(options.robot, read);
  std::vector<LinkComparison> links;
  bool failed = false;
  for (const robot::Link& link : robot.links) {
    links.push_back(compare_link(link, robot::compute_link_inertial(link, options.compute)));
    if (links.back().result.error) {
      err << "tumble inertials: error: " << robot.file.string() << ": "
          << *links.back().result.error << "\n";
      failed = true;
    }
  }
  const std::string source =
      options.from == robot::GeometrySource::collision ? "collision" : "visual";
  if (options.json) {
    out << comparison_to_json(robot, links, source, options.tolerance, options.check).dump(2)
        << "\n";
  } else {
    out << format_comparison(robot, links, source, options.tolerance, options.check);
  }
  if (failed) {
    if (options.output) {
      err << "tumble inertials: nothing written to '" << options.output->string()
          << "': a link failed\n";
    }
    return kExitInputError;
  }
  if (options.output) {
    std::vector<std::optional<engine::MassProperties>> inertials;
    for (const LinkComparison& link : links) {
      inertials.push_back(link.result.computed
                              ? std::optional(written_inertial(*link.result.computed))
                              : std::nullopt);
    }
    write_atomically(*options.output, options.robot,
                     robot::rewritten_text(robot, inertials, options.frame));
  }
  if (options.check) {
    for (const LinkComparison& link : links) {
      if (!within_tolerance(link, options.tolerance)) return kExitCheckFailed;
    }
  }
  return kExitDone;
}

}  // namespace

int run_inertials(const InertialsOptions& options, std::ostream& out, std::ostream& err) {
  return run_guarded("inertials", err, [&] { return inertials(options, out, err); });
}

}  // namespace tumble::app
