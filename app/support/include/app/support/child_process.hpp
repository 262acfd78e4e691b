#pragma once
/// @file Running a tool (ffprobe, ffmpeg) as a child process and collecting what it says: for
/// the commands of the `tumble` executable, which must not link the renderer's ffmpeg pipe.

#include <functional>
#include <string>
#include <vector>

namespace tumble::app {

/// How a child process ended and what it wrote.
struct ChildResult {
  int status = -1;         ///< its exit status; -1 if a signal (or we) ended it
  bool cancelled = false;  ///< `cancel` said so and the child was killed
  std::string out;         ///< all of its stdout
  std::string err;         ///< the tail of its stderr (the last 16 KiB)
};

/// Runs `argv` (argv[0] looked up on PATH) with stdin from /dev/null, collecting its stdout
/// and stderr, until it exits. `cancel`, when given, is asked about every 100 ms; once it
/// returns true the child is killed (SIGKILL) and waited for. Throws tumble::InputError
/// "ARGV0 not found on PATH" (or cannot be executed), std::runtime_error when the system gives
/// no pipe or process.
ChildResult run_child(const std::vector<std::string>& argv,
                      const std::function<bool()>& cancel = {});

/// The last two non-empty lines of a tool's stderr on one line ("no message on stderr" when
/// there are none), for a one-line error.
std::string last_lines(const std::string& text);

}  // namespace tumble::app
