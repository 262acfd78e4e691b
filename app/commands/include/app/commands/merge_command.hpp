#pragma once
/// @file `tumble merge PART... -o OUT`: the parts of a sharded command (`--shard I/N`) checked
/// to be one job's, each shard exactly once, and joined into the output the unsharded command
/// would have written (docs/merge.md).

#include <filesystem>
#include <iosfwd>
#include <vector>

namespace CLI {
class App;
}  // namespace CLI

namespace tumble::app {

/// What `tumble merge` was asked to do.
struct MergeOptions {
  std::vector<std::filesystem::path> parts;
  std::filesystem::path output;
  bool quiet = false;
};

/// Adds the `merge` subcommand and its options to `cli`, filling `options` when parsed.
CLI::App& add_merge_command(CLI::App& cli, MergeOptions& options);

/// Runs the command. Returns 0, kExitInputError (1) with one line on `err` (a missing,
/// duplicated or foreign part, named), or kExitInterrupted (nothing written).
int run_merge(const MergeOptions& options, std::ostream& out, std::ostream& err);

}  // namespace tumble::app
