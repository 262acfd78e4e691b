#pragma once
/// @file `tumble compare`: its options (the job is app/video/compare_job.hpp).

#include <iosfwd>

#include "app/video/compare_job.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace tumble::app {

/// Adds the `compare` subcommand and its options to `cli`, filling `options` when parsed.
CLI::App& add_compare_command(CLI::App& cli, CompareOptions& options);

/// Runs the command. Returns 0, 1 (input, output or ffmpeg error: one line on `err`, nothing
/// left under the output name), 3 (some run blew up: the output is complete, one warning line
/// per blown-up run on `err`) or kExitInterrupted. A summary line goes to `out` unless --quiet.
int run_compare(const CompareOptions& options, std::ostream& out, std::ostream& err);

}  // namespace tumble::app
