// `tumble merge`: reads every part's manifest and hands the parts to the merge of their kind
// (app/farm/part_kind.hpp), looked up by name.
#include "app/commands/merge_command.hpp"

#include <ostream>

#include <CLI/CLI.hpp>

#include "app/analysis/row_part_kinds.hpp"
#include "app/farm/part_kind.hpp"
#include "app/inspect/inspect_parts.hpp"
#include "app/support/exit_status.hpp"
#include "app/support/interrupt_guard.hpp"
#include "app/video_parts/video_merge.hpp"

namespace tumble::app {

namespace {

/// Every kind of part this tumble merges.
const PartKinds& known_part_kinds() {
  static const PartKinds kinds(
      {&bench_parts(), &stability_parts(), &inspect_parts(), &render_parts(), &compare_parts()});
  return kinds;
}

int merge_to_output(const MergeOptions& options, const InterruptGuard& guard, std::ostream& out,
                    std::ostream& err) {
  const MergeOutcome merged = merge_parts(known_part_kinds(), options.parts, options.output,
                                          [&] { return guard.interrupted(); });
  if (merged.interrupted) {
    guard.report(err, "merge", options.output.string());
    return kExitInterrupted;
  }
  if (!options.quiet) out << merged.summary;
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
      "merge", err, [&] { return merge_to_output(options, guard, out, err); },
      [&] {
        if (!guard.interrupted()) return -1;
        guard.report(err, "merge", options.output.string());
        return kExitInterrupted;
      });
}

}  // namespace tumble::app
