#pragma once
/// @file `tumble merge PART... -o OUT`: the parts of a sharded job (`--shard I/N` of bench,
/// stability, inspect, render, compare) checked to be of one job and to cover it exactly once,
/// then joined into the output the unsharded command writes (README, "More than one machine").

#include <filesystem>
#include <iosfwd>
#include <vector>

namespace CLI {
class App;
}  // namespace CLI

namespace tumble::app {

/// What `tumble merge` was asked to do.
struct MergeOptions {
  std::vector<std::filesystem::path> parts;  ///< in any order (the manifests say which is which)
  std::filesystem::path output;
};

/// Adds the `merge` subcommand and its options to `cli`, filling `options` when parsed.
CLI::App& add_merge_command(CLI::App& cli, MergeOptions& options);

/// Runs the command. Returns 0, or 1 with one line on `err` naming the part at fault (missing,
/// duplicated, of another job or kind, edited) or the output that cannot be written; nothing
/// is written at the output then.
int run_merge(const MergeOptions& options, std::ostream& out, std::ostream& err);

}  // namespace tumble::app
