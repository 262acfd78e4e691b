// `tumble inspect`.
#include "app/commands/inspect_command.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <optional>
#include <ostream>
#include <sstream>
#include <thread>
#include <utility>

#include <CLI/CLI.hpp>

#include "app/commands/exit_status.hpp"
#include "app/farm/shard.hpp"
#include "app/scene/mesh_inspection.hpp"
#include "app/scene/unit_hint.hpp"
#include "app/support/csv_writer.hpp"
#include "base/errors.hpp"
#include "inspect_inputs.hpp"
#include "inspect_output.hpp"
#include "inspect_part.hpp"
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
  } catch (const tumble::InputError& error) {
    outcome.error = error.what();
  } catch (...) {
    outcome.failure = std::current_exception();
  }
  return outcome;
}

/// The shard of --shard, after checking that -o names a .jsonl part and no other format is
/// asked for; none without --shard.
std::optional<Shard> inspect_shard(const InspectOptions& options) {
  if (!options.shard) return std::nullopt;
  const Shard shard = parse_shard(*options.shard);
  if (!options.output) throw tumble::InputError("--shard: -o FILE.jsonl is required (the part)");
  if (options.output->extension() != ".jsonl") {
    throw tumble::InputError("--shard: -o " + options.output->string() +
                             ": a part is JSON Lines; expected a name ending in .jsonl");
  }
  if (options.format_given && options.format != InspectFormat::jsonl) {
    throw tumble::InputError("--shard: a part is JSON Lines; drop --format (or use jsonl)");
  }
  return shard;
}

/// The command: expand the inputs, inspect them (a shard: its files) on the jobs' threads,
/// print in input order, on stdout or into -o FILE.
int inspect(const InspectOptions& given, std::ostream& out, std::ostream& err) {
  const std::optional<Shard> shard = inspect_shard(given);
  InspectOptions options = given;
  if (shard) options.format = InspectFormat::jsonl;
  bool batch = false;
  const std::vector<InspectInput> inputs =
      expand_inspect_inputs(options.files, options.recursive, batch);
  std::vector<std::size_t> items;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    if (!shard || in_shard(i, inputs.size(), *shard, ShardSplit::kStrided)) items.push_back(i);
  }
  // -o is checked (and its temporary opened) before any file is read.
  std::optional<AtomicFile> file;
  if (options.output) {
    std::vector<std::filesystem::path> files;
    for (const InspectInput& input : inputs) files.push_back(input.file);
    file.emplace(*options.output, files);
  }
  std::ostringstream buffer;
  InspectPrinter printer(options, file ? buffer : out, err, batch || inputs.size() > 1);
  unsigned jobs = options.jobs;
  if (jobs == 0) jobs = std::max(1u, std::thread::hardware_concurrency());
  // The cores left by the files inspected at once go to each file's overlap checks.
  options.mass.jobs = std::max(1u, std::thread::hardware_concurrency() / jobs);
  // Each file's outcome waits in its slot until every file before it is printed.
  std::vector<InspectOutcome> outcomes(items.size());
  std::vector<std::string> digests(shard ? items.size() : 0);
  run_ordered(
      items.size(), jobs,
      [&](std::size_t k) {
        outcomes[k] = inspect_one(inputs[items[k]], options.mass);
        if (shard) digests[k] = digest_or_unreadable(inputs[items[k]].file);
      },
      [&](std::size_t k) {
        printer.print(inputs[items[k]].file, std::exchange(outcomes[k], {}),
                      shard ? nlohmann::json{{"item", items[k]}} : nlohmann::json());
      });
  const int status = printer.finish();
  if (!file) return status;
  // json prints nothing unless every file succeeded: then nothing is written either.
  if (status != kExitDone && options.format == InspectFormat::json) return status;
  if (shard) {
    file->write(inspect_part_line(inspect_job(options, inputs, batch), *shard, inputs.size(), items,
                                  digests));
  }
  file->write(buffer.str());
  file->commit();
  return status;
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
  inspect.add_flag("--allow-overlap", options.mass.allow_overlap,
                   "Accept parts that overlap, intersect themselves or repeat (their shared "
                   "volume counts twice; a warning says how much); by default an error");
  inspect.add_flag_callback(
      "--skip-overlap-checks", [&options] { options.mass.check_overlap = false; },
      "Do not test the parts' faces for crossings, self-intersections and repeats (their "
      "containment in each other is still decided; parts that cross may be taken as nested)");
  add_output_options(inspect, options);
  add_batch_options(inspect, options);
  return inspect;
}

Eigen::Vector3d parse_scale_factors(const std::string& text) {
  const auto refuse = [&] {
    return tumble::InputError(
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
