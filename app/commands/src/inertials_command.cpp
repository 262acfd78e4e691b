// `tumble inertials`.
#include "app/commands/inertials_command.hpp"

#include <cmath>
#include <exception>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/support/exit_status.hpp"
#include "inertia_option.hpp"
#include "overlap_option.hpp"

namespace tumble::app {
namespace {

/// A positive finite number of `option`'s value `text`, or throws CLI::ValidationError.
double positive_value(const std::string& option, const std::string& text,
                      const std::string& value) {
  std::size_t used = 0;
  double number = 0.0;
  try {
    number = std::stod(value, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != value.size() || !std::isfinite(number) || number <= 0.0) {
    throw CLI::ValidationError(option,
                               "'" + text + "': expected a positive number, got '" + value + "'");
  }
  return number;
}

/// LINK=VALUE of `option`.
std::pair<std::string, double> link_value(const std::string& option, const std::string& text) {
  const std::size_t equals = text.rfind('=');
  if (equals == std::string::npos || equals == 0) {
    throw CLI::ValidationError(option, "'" + text + "': expected LINK=VALUE");
  }
  return {text.substr(0, equals), positive_value(option, text, text.substr(equals + 1))};
}

/// --density RHO or --density LINK=RHO.
void add_density(const std::string& text, robot::ComputeOptions& compute) {
  if (text.find('=') == std::string::npos) {
    compute.density = positive_value("--density", text, text);
  } else {
    compute.link_densities.push_back(link_value("--density", text));
  }
}

/// --density RHO|LINK=RHO, --mass LINK=M, --total-mass M.
void add_weighed_mass_options(CLI::App& command, robot::ComputeOptions& compute) {
  command
      .add_option_function<std::vector<std::string>>(
          "--density",
          [&](const std::vector<std::string>& values) {
            for (const std::string& value : values) add_density(value, compute);
          },
          "RHO: kg/m^3 for every link: the masses follow from the volumes (default: keep each "
          "link's stated mass; 1000 for a link stating none). LINK=RHO (repeatable): that "
          "link's density, over the file's own (SDF collision, MJCF geom) and over RHO")
      ->allow_extra_args(false)
      ->option_text("RHO|LINK=RHO");
  command
      .add_option_function<std::vector<std::string>>(
          "--mass",
          [&](const std::vector<std::string>& values) {
            for (const std::string& value : values) {
              compute.link_masses.push_back(link_value("--mass", value));
            }
          },
          "LINK=M (repeatable): that link's weighed mass in kg; its centre of mass and inertia "
          "follow from the geometry, the inertia scaled to M")
      ->allow_extra_args(false)
      ->option_text("LINK=M");
  command
      .add_option_function<double>(
          "--total-mass", [&](double value) { compute.total_mass = value; },
          "The whole robot's weighed mass in kg, spread over the links in proportion to their "
          "masses from densities (links with --mass, and links without geometry that keep a "
          "stated mass, are subtracted first)")
      ->check(CLI::PositiveNumber)
      ->option_text("M");
}

}  // namespace

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
  add_weighed_mass_options(command, options.compute);
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
  add_overlap_options(command, options.compute.overlap);
  add_inertia_option(command, options.compute.inertia);
  command
      .add_option_function<double>(
          "--shell",
          [&](double value) {
            options.compute.shell_thickness = value;
            options.compute.inertia = engine::InertiaMethod::shell;
          },
          "Meshes as thin shells of THICKNESS metres (implies --inertia shell; without it a "
          "shell's density is per area, kg/m^2)")
      ->check(CLI::PositiveNumber);
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

int run_inertials(const InertialsOptions& options, std::ostream& out, std::ostream& err) {
  return run_guarded("inertials", err, [&] { return write_inertials(options, out, err); });
}

}  // namespace tumble::app
