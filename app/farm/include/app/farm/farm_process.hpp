#pragma once
/// @file Running a program (sbatch, scontrol, bash) as `tumble farm` does: by its arguments, no
/// shell in between, its standard output and error captured.

#include <string>
#include <vector>

namespace tumble::app {

struct ProcessResult {
  int status = -1;  ///< exit status; 128 + N when killed by signal N; 127 when it cannot start
  std::string out;
  std::string err;
};

/// Runs `argv` (argv[0] looked up on PATH) with standard input from /dev/null and waits for it.
/// A program that cannot be started gives status 127 and the reason in `err`.
ProcessResult run_process(const std::vector<std::string>& argv);

/// Runs `argv` with this process's standard input, output and error, and waits for it; its exit
/// status as run_process gives it.
int run_attached(const std::vector<std::string>& argv);

/// The last non-empty line of `text` (a tool's stderr, for a one-line message).
std::string last_line(const std::string& text);

}  // namespace tumble::app
