// `tumble inspect`.
#include "app/commands/inspect_command.hpp"

#include <map>
#include <ostream>

#include <CLI/CLI.hpp>

#include "app/inspect/inspect_run.hpp"
#include "app/support/exit_status.hpp"
#include "base/errors.hpp"
#include "inertia_option.hpp"
#include "overlap_option.hpp"

namespace tumble::app {
namespace {

/// --format and its aliases, --frame.
void add_output_options(CLI::App& inspect, InspectOptions& options) {
  const std::map<std::string, InspectFormat> formats = {
      {"text", InspectFormat::text}, {"json", InspectFormat::json}, {"jsonl", InspectFormat::jsonl},
      {"urdf", InspectFormat::urdf}, {"sdf", InspectFormat::sdf},   {"mjcf", InspectFormat::mjcf}};
  auto* format =
      inspect
          .add_option_function<std::string>(
              "--format",
              [&options, formats](const std::string& name) {
                options.format = formats.at(name);
                options.format_given = true;
              },
              "text (the table, default); json (one object, an array for a batch; nothing "
              "unless every file succeeds); jsonl (one object a line per file as it finishes, "
              "errors as {\"file\", \"error\"}); urdf, sdf, mjcf (the inertial element)")
          ->transform(CLI::IsMember(formats, CLI::ignore_case))
          ->option_text("text|json|jsonl|urdf|sdf|mjcf");
  inspect
      .add_flag_callback(
          "--json",
          [&] {
            options.format = InspectFormat::json;
            options.format_given = true;
          },
          "Same as --format json")
      ->excludes(format);
  inspect
      .add_flag_callback(
          "--jsonl",
          [&] {
            options.format = InspectFormat::jsonl;
            options.format_given = true;
          },
          "Same as --format jsonl")
      ->excludes(format);
  const std::map<std::string, robot::InertialFrame> frames = {
      {"mesh", robot::InertialFrame::mesh}, {"principal", robot::InertialFrame::principal}};
  inspect
      .add_option_function<std::string>(
          "--frame",
          [&options, frames](const std::string& name) { options.frame = frames.at(name); },
          "Frame of the urdf/sdf/mjcf inertia: mesh (the file's axes, rotation zero, all six "
          "elements; default) or principal (the principal axes' rotation and moments); json "
          "has both and ignores it")
      ->transform(CLI::IsMember(frames, CLI::ignore_case))
      ->option_text("mesh|principal");
}

/// -r and --jobs.
void add_batch_options(CLI::App& inspect, InspectOptions& options) {
  inspect.add_flag("-r,--recursive", options.recursive,
                   "Directories: take the mesh files below them too, not only directly inside");
  inspect
      .add_option("--jobs", options.jobs,
                  "Files inspected at once (default 1; 0: one per core); output stays in input "
                  "order. The cores left over split each file's overlap checks")
      ->check(CLI::NonNegativeNumber);
  inspect.add_option_function<std::string>(
      "-o,--output", [&](const std::string& value) { options.output = value; },
      "Write the output to FILE (atomically) instead of stdout; with --shard, the part "
      "(FILE.jsonl)");
  inspect.add_option_function<std::string>(
      "--shard", [&](const std::string& value) { options.shard = value; },
      "I/N: inspect only the I-th of N shards of the file list (I from 0; every N-th file) and "
      "write -o FILE.jsonl as a part for tumble merge");
}

}  // namespace

CLI::App& add_inspect_command(CLI::App& cli, InspectOptions& options) {
  CLI::App& inspect = *cli.add_subcommand(
      "inspect",
      "Mass properties of meshes: volume, mass, centre of mass, inertia, principal axes");
  inspect
      .add_option("MESH", options.files,
                  "Mesh files (STL, OBJ, PLY, OFF, glTF, FBX, ...), directories of them and "
                  "@LIST files (one path a line, relative to the list; # comments)")
      ->required();
  auto* density = inspect.add_option_function<double>(
      "--density", [&](double value) { options.mass.density = value; },
      "Density in kg/m^3 (default 1000, water)");
  inspect
      .add_option_function<double>(
          "--mass", [&](double value) { options.mass.mass = value; },
          "Total mass in kg (the density follows)")
      ->excludes(density);
  inspect.add_option_function<std::string>(
      "--scale",
      [&](const std::string& text) {
        try {
          options.mass.scale = parse_scale_factors(text);
        } catch (const tumble::InputError& error) {
          throw CLI::ValidationError(error.what());
        }
      },
      "File units to metres: one factor (0.001 for millimetres) or three, sx,sy,sz, as URDF's "
      "<mesh scale>; a negative factor mirrors (default 1)");
  inspect.add_option_function<double>(
      "--shell", [&](double value) { options.mass.shell_thickness = value; },
      "Thin-shell mode: THICKNESS in metres; area-weighted, for sheets and open surfaces");
  add_inertia_option(inspect, options.mass.inertia);
  add_overlap_options(inspect, options.mass.overlap);
  inspect.add_flag_callback(
      "--skip-overlap-checks", [&options] { options.mass.check_overlap = false; },
      "Do not test the parts' faces for crossings, self-intersections and repeats (their "
      "containment in each other is still decided; parts that cross may be taken as nested)");
  add_output_options(inspect, options);
  add_batch_options(inspect, options);
  return inspect;
}

int run_inspect(const InspectOptions& options, std::ostream& out, std::ostream& err) {
  return run_guarded("inspect", err, [&] { return write_inspection(options, out, err); });
}

}  // namespace tumble::app
