// `tumble inspect`.
#include "app/commands/inspect_command.hpp"

#include <cmath>
#include <cstdio>
#include <ostream>
#include <sstream>

#include <CLI/CLI.hpp>

#include "app/commands/exit_status.hpp"
#include "app/scene/mesh_inspection.hpp"
#include "engine/input_error.hpp"

namespace tumble::app {

CLI::App& add_inspect_command(CLI::App& cli, InspectOptions& options) {
  CLI::App& inspect = *cli.add_subcommand(
      "inspect",
      "Mass properties of meshes: volume, mass, centre of mass, inertia, principal axes");
  inspect.add_option("MESH", options.files, "Mesh files (STL, OBJ, PLY, OFF, glTF, FBX, ...)")
      ->required();
  auto* density = inspect.add_option_function<double>(
      "--density", [&](double value) { options.mass.density = value; },
      "Density in kg/m^3 (default 1000, water)");
  inspect
      .add_option_function<double>(
          "--mass", [&](double value) { options.mass.mass = value; },
          "Total mass in kg (the density follows)")
      ->excludes(density);
  inspect.add_option_function<double>(
      "--scale", [&](double value) { options.mass.scale = Eigen::Vector3d::Constant(value); },
      "File units to metres, e.g. 0.001 for millimetres (default 1)");
  inspect.add_option_function<double>(
      "--shell", [&](double value) { options.mass.shell_thickness = value; },
      "Thin-shell mode: THICKNESS in metres; area-weighted, for sheets and open surfaces");
  inspect.add_flag("--allow-overlap", options.mass.allow_overlap,
                   "Accept parts that overlap, intersect themselves or repeat (their shared "
                   "volume counts twice; a warning says how much); by default an error");
  inspect.add_flag("--json", options.json, "Print JSON (an array when several files are given)");
  return inspect;
}

namespace {

int inspect(const InspectOptions& options, std::ostream& out, std::ostream& err) {
  std::vector<engine::MeshReport> reports;
  int status = 0;
  for (const std::filesystem::path& file : options.files) {
    try {
      reports.push_back(inspect_file(file, options.mass));
    } catch (const engine::InputError& error) {
      err << "tumble inspect: error: " << error.what() << "\n";
      status = kExitInputError;
    }
  }
  if (options.json) {
    if (status != 0) return status;
    if (reports.size() == 1) {
      out << report_to_json(reports.front()).dump(2) << "\n";
    } else {
      nlohmann::json array = nlohmann::json::array();
      for (const auto& report : reports) array.push_back(report_to_json(report));
      out << array.dump(2) << "\n";
    }
    return 0;
  }
  for (std::size_t i = 0; i < reports.size(); ++i)
    out << (i ? "\n" : "") << format_report(reports[i]);
  return status;
}

}  // namespace

int run_inspect(const InspectOptions& options, std::ostream& out, std::ostream& err) {
  return run_guarded("inspect", err, [&] { return inspect(options, out, err); });
}

}  // namespace tumble::app
