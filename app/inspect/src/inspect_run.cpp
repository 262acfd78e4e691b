// `tumble inspect`'s run: the inputs inspected on the jobs' threads, in input order.
#include "app/inspect/inspect_run.hpp"

#include <algorithm>
#include <ostream>
#include <sstream>
#include <thread>
#include <utility>

#include "app/farm/shard.hpp"
#include "app/inspect/inspect_inputs.hpp"
#include "app/inspect/inspect_output.hpp"
#include "app/inspect/inspect_parts.hpp"
#include "app/scene/mesh_inspection.hpp"
#include "app/scene/unit_hint.hpp"
#include "app/support/csv_writer.hpp"
#include "app/support/exit_status.hpp"
#include "app/support/interrupt_guard.hpp"
#include "app/support/ordered_parallel.hpp"
#include "base/errors.hpp"

namespace tumble::app {
namespace {

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

unsigned inspect_jobs(unsigned jobs) {
  return jobs == 0 ? std::max(1u, std::thread::hardware_concurrency()) : jobs;
}

/// `options` with the cores left by the files inspected at once given to each file's overlap
/// checks.
InspectOptions with_check_threads(InspectOptions options) {
  options.mass.jobs =
      std::max(1u, std::thread::hardware_concurrency() / inspect_jobs(options.jobs));
  return options;
}

}  // namespace

std::vector<InspectResult> inspect_files(const InspectOptions& given) {
  const InspectOptions options = with_check_threads(given);
  bool batch = false;
  const std::vector<InspectInput> inputs =
      expand_inspect_inputs(options.files, options.recursive, batch);
  std::vector<InspectOutcome> outcomes(inputs.size());
  std::vector<InspectResult> results;
  results.reserve(inputs.size());
  run_ordered(
      inputs.size(), inspect_jobs(options.jobs),
      [&](std::size_t k) { outcomes[k] = inspect_one(inputs[k], options.mass); },
      [&](std::size_t k) {
        InspectOutcome outcome = std::exchange(outcomes[k], {});
        if (outcome.failure) std::rethrow_exception(outcome.failure);
        results.push_back({inputs[k].file, std::move(outcome.report), std::move(outcome.error)});
      });
  return results;
}

nlohmann::json inspect_json(const engine::MeshReport& report) {
  return report_to_json(report);
}

int write_inspection(const InspectOptions& given, std::ostream& out, std::ostream& err) {
  const std::optional<Shard> shard = inspect_shard(given);
  InspectOptions options = with_check_threads(given);
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
  // Ctrl-C or SIGTERM: the files not yet started are skipped, nothing more is printed, and the
  // -o file's temporary is removed (the process used to die with it left behind).
  const InterruptGuard guard;
  std::ostringstream buffer;
  InspectPrinter printer(options, file ? buffer : out, err, batch || inputs.size() > 1);
  // Each file's outcome waits in its slot until every file before it is printed.
  std::vector<InspectOutcome> outcomes(items.size());
  std::vector<std::string> digests(shard ? items.size() : 0);
  run_ordered(
      items.size(), inspect_jobs(options.jobs),
      [&](std::size_t k) {
        if (guard.interrupted()) return;
        outcomes[k] = inspect_one(inputs[items[k]], options.mass);
        if (shard) digests[k] = digest_or_unreadable(inputs[items[k]].file);
      },
      [&](std::size_t k) {
        if (guard.interrupted()) return;
        printer.print(inputs[items[k]].file, std::exchange(outcomes[k], {}),
                      shard ? nlohmann::json{{"item", items[k]}} : nlohmann::json());
      });
  if (guard.interrupted()) {
    guard.report(err, "inspect", options.output ? options.output->string() : std::string());
    return kExitInterrupted;
  }
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

}  // namespace tumble::app
