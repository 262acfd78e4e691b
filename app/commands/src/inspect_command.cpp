// `tumble inspect`.
#include "app/commands/inspect_command.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <ostream>
#include <thread>
#include <utility>

#include <CLI/CLI.hpp>

#include "app/commands/exit_status.hpp"
#include "app/scene/mesh_inspection.hpp"
#include "app/scene/unit_hint.hpp"
#include "engine/input_error.hpp"
#include "inspect_inputs.hpp"
#include "inspect_output.hpp"
#include "ordered_parallel.hpp"

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
              [&options, formats](const std::string& name) { options.format = formats.at(name); },
              "text (the table, default); json (one object, an array for a batch; nothing "
              "unless every file succeeds); jsonl (one object a line per file as it finishes, "
              "errors as {\"file\", \"error\"}); urdf, sdf, mjcf (the inertial element)")
          ->transform(CLI::IsMember(formats, CLI::ignore_case))
          ->option_text("text|json|jsonl|urdf|sdf|mjcf");
  inspect
      .add_flag_callback(
          "--json", [&] { options.format = InspectFormat::json; }, "Same as --format json")
      ->excludes(format);
  inspect
      .add_flag_callback(
          "--jsonl", [&] { options.format = InspectFormat::jsonl; }, "Same as --format jsonl")
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
                  "order")
      ->check(CLI::NonNegativeNumber);
}

/// One file's inspection, every error caught into the outcome.
InspectOutcome inspect_one(const InspectInput& input, const engine::MassOptions& mass) {
  InspectOutcome outcome;
  if (!input.error.empty()) {
    outcome.error = input.error;
    return outcome;
  }
  try {
    engine::MeshReport report = inspect_file(input.file, mass);
    if (auto hint = unit_hint(report, mass.scale)) report.warnings.push_back(std::move(*hint));
    outcome.report = std::move(report);
  } catch (const engine::InputError& error) {
    outcome.error = error.what();
  } catch (...) {
    outcome.failure = std::current_exception();
  }
  return outcome;
}

/// The command: expand the inputs, inspect them on the jobs' threads, print in input order.
int inspect(const InspectOptions& options, std::ostream& out, std::ostream& err) {
  bool batch = false;
  const std::vector<InspectInput> inputs =
      expand_inspect_inputs(options.files, options.recursive, batch);
  InspectPrinter printer(options, out, err, batch || inputs.size() > 1);
  unsigned jobs = options.jobs;
  if (jobs == 0) jobs = std::max(1u, std::thread::hardware_concurrency());
  // Each file's outcome waits in its slot until every file before it is printed.
  std::vector<InspectOutcome> outcomes(inputs.size());
  run_ordered(
      inputs.size(), jobs,
      [&](std::size_t i) { outcomes[i] = inspect_one(inputs[i], options.mass); },
      [&](std::size_t i) { printer.print(inputs[i].file, std::exchange(outcomes[i], {})); });
  return printer.finish();
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
        } catch (const engine::InputError& error) {
          throw CLI::ValidationError(error.what());
        }
      },
      "File units to metres: one factor (0.001 for millimetres) or three, sx,sy,sz, as URDF's "
      "<mesh scale>; a negative factor mirrors (default 1)");
  inspect.add_option_function<double>(
      "--shell", [&](double value) { options.mass.shell_thickness = value; },
      "Thin-shell mode: THICKNESS in metres; area-weighted, for sheets and open surfaces");
  inspect.add_flag("--allow-overlap", options.mass.allow_overlap,
                   "Accept parts that overlap, intersect themselves or repeat (their shared "
                   "volume counts twice; a warning says how much); by default an error");
  add_output_options(inspect, options);
  add_batch_options(inspect, options);
  return inspect;
}

Eigen::Vector3d parse_scale_factors(const std::string& text) {
  const auto refuse = [&] {
    return engine::InputError(
        "--scale: expected one factor or three (sx,sy,sz), each finite "
        "and non-zero, got \"" +
        text + "\"");
  };
  std::vector<double> factors;
  std::size_t begin = 0;
  while (true) {
    const std::size_t end = std::min(text.find(',', begin), text.size());
    double value = 0.0;
    const char* first = text.data() + begin;
    const char* last = text.data() + end;
    if (first != last && *first == '+') ++first;  // from_chars takes no '+'
    const auto [ptr, ec] = std::from_chars(first, last, value);
    if (ec != std::errc() || ptr != last || !std::isfinite(value) || value == 0.0) throw refuse();
    factors.push_back(value);
    if (end == text.size()) break;
    begin = end + 1;
  }
  if (factors.size() == 1) return Eigen::Vector3d::Constant(factors[0]);
  if (factors.size() == 3) return {factors[0], factors[1], factors[2]};
  throw refuse();
}

int run_inspect(const InspectOptions& options, std::ostream& out, std::ostream& err) {
  return run_guarded("inspect", err, [&] { return inspect(options, out, err); });
}

}  // namespace tumble::app
