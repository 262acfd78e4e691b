// `tumble inertials`.
#include "app/commands/inertials_command.hpp"

#include <ostream>

#include <CLI/CLI.hpp>

#include "app/support/exit_status.hpp"
#include "inertia_option.hpp"
#include "overlap_option.hpp"

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
