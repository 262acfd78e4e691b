// `tumble merge`: read every part's manifest, check that they cover one job exactly once, and
// hand them to the merge of their kind.
#include "app/commands/merge_command.hpp"

#include <ostream>
#include <string>

#include <CLI/CLI.hpp>

#include "app/commands/exit_status.hpp"
#include "app/farm/part_manifest.hpp"
#include "merge_rows.hpp"
#include "tumble/errors.hpp"

namespace tumble::app {
namespace {

int merge(const MergeOptions& options, std::ostream& out) {
  if (options.parts.empty()) throw InputError("expected the parts to merge (PART...)");
  if (options.output.empty()) throw InputError("-o OUT is required");
  std::vector<NamedManifest> given;
  for (const std::filesystem::path& part : options.parts) {
    given.push_back({part, read_part_manifest(part)});
  }
  std::vector<NamedManifest> parts;
  for (const std::size_t i : check_parts_cover_job(given)) parts.push_back(given[i]);
  const std::string& kind = parts.front().manifest.kind;
  if (kind == "bench" || kind == "stability") {
    merge_row_parts(parts, options.output, out);
  } else if (kind == "inspect") {
    merge_inspect_parts(parts, options.output, out);
  } else if (kind == "render" || kind == "compare") {
    throw InputError(kind + " parts: this tumble does not merge video parts yet ('" +
                     parts.front().part.string() + "')");
  } else {
    throw InputError(parts.front().part.string() + ": a part of kind '" + kind +
                     "', which tumble merge does not know");
  }
  return kExitDone;
}

}  // namespace

CLI::App& add_merge_command(CLI::App& cli, MergeOptions& options) {
  CLI::App& command = *cli.add_subcommand(
      "merge",
      "Join the parts of a sharded bench, stability, inspect, render or compare (--shard I/N) "
      "into the output of the unsharded command");
  command
      .add_option("PART", options.parts,
                  "The parts: folders (bench, stability, PNG frames), .jsonl files (inspect), "
                  "video segments; any order")
      ->required();
  command
      .add_option("-o,--output", options.output,
                  "The output: a folder (bench, stability), .jsonl or .json (inspect), a "
                  "video or PNG folder (render, compare); written atomically")
      ->required();
  return command;
}

int run_merge(const MergeOptions& options, std::ostream& out, std::ostream& err) {
  return run_guarded("merge", err, [&] { return merge(options, out); });
}

}  // namespace tumble::app
