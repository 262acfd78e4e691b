// `tumble merge`: reads every part's manifest and hands the parts to the merge of their kind.
#include "app/commands/merge_command.hpp"

#include <ostream>

#include <CLI/CLI.hpp>

#include "app/commands/exit_status.hpp"
#include "app/farm/part_manifest.hpp"
#include "app/support/interrupt_guard.hpp"
#include "merge_rows.hpp"
#include "merge_video.hpp"

namespace tumble::app {

namespace {

int merge_parts(const MergeOptions& options, const InterruptGuard& guard, std::ostream& out,
                std::ostream& err) {
  std::vector<NamedManifest> parts;
  for (const std::filesystem::path& part : options.parts) {
    parts.push_back({part, read_part_manifest(part)});
  }
  const std::string& kind = parts.front().manifest.kind;
  if (kind == "bench" || kind == "stability" || kind == "inspect") {
    std::vector<NamedManifest> ordered;
    for (const std::size_t i : check_parts_cover_job(parts)) ordered.push_back(parts[i]);
    if (kind == "inspect") {
      merge_inspect_parts(ordered, options.output, out);
    } else {
      merge_row_parts(ordered, options.output, out);
    }
    return kExitDone;
  }
  if (kind != "render" && kind != "compare") {
    throw InputError(parts.front().part.string() + ": " + kind +
                     " parts cannot be merged by this tumble");
  }
  const VideoMerge merge =
      merge_video_parts(parts, options.output, [&] { return guard.interrupted(); });
  if (merge.interrupted) {
    guard.report(err, "merge", options.output.string());
    return kExitInterrupted;
  }
  if (!options.quiet) {
    out << "tumble merge: " << parts.size() << (parts.size() == 1 ? " part, " : " parts, ")
        << merge.frames << (merge.frames == 1 ? " frame" : " frames") << " written to '"
        << options.output.string() << "'" << (merge.copied ? " (joined without re-encoding)" : "")
        << "\n";
  }
  return kExitDone;
}

}  // namespace

CLI::App& add_merge_command(CLI::App& cli, MergeOptions& options) {
  CLI::App& merge = *cli.add_subcommand(
      "merge", "Join the parts of a sharded command (--shard I/N) into its whole output");
  merge.footer(
      "Every part must be of one job (the same command, inputs and options), and every shard "
      "0..N-1 must be given once. render/compare parts: PNG folders or .mp4/.webm segments; OUT "
      "is a .mp4, .webm, .gif or DIR/ (segments of OUT's format are joined without "
      "re-encoding). The output is written atomically. Exit status: 0 done, 1 a missing, "
      "duplicated or foreign part, or ffmpeg failing, 130 interrupted (nothing written).");
  merge.add_option("PART", options.parts, "The parts, in any order")->required()->type_name("PART");
  merge
      .add_option_function<std::string>(
          "-o,--output", [&](const std::string& value) { options.output = value; },
          "The merged output")
      ->required()
      ->type_name("OUT");
  merge.add_flag("-q,--quiet", options.quiet, "No summary line");
  return merge;
}

int run_merge(const MergeOptions& options, std::ostream& out, std::ostream& err) {
  const InterruptGuard guard;
  return run_guarded(
      "merge", err, [&] { return merge_parts(options, guard, out, err); },
      [&] {
        if (!guard.interrupted()) return -1;
        guard.report(err, "merge", options.output.string());
        return kExitInterrupted;
      });
}

}  // namespace tumble::app
