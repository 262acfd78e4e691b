#pragma once
/// @file The one mapping from what a command's run came to, to its exit status, for every
/// command (and main()'s parse errors).
///
///   0    done
///   1    bad input: a tumble::InputError (scene, mesh, option, output path, ffmpeg failing on
///        the output), reported as one line naming the file and field
///   3    the run blew up (its outputs are still written, as each command documents)
///   4    `inertials --check`: a link's stated inertial differs from its geometry's by more
///        than the tolerance
///   70   internal error: any other exception, which is a bug in tumble, never "bad input"
///   130  interrupted by SIGINT or SIGTERM (nothing left under the output name)

#include <exception>
#include <ostream>
#include <string_view>

#include "base/errors.hpp"

namespace tumble::app {

inline constexpr int kExitDone = 0;
inline constexpr int kExitInputError = 1;
inline constexpr int kExitBlowUp = 3;
inline constexpr int kExitCheckFailed = 4;
inline constexpr int kExitInternalError = 70;
inline constexpr int kExitInterrupted = 130;

/// Runs `body` (which returns an exit status) and maps what escapes it: an InputError is one
/// line "tumble COMMAND: error: ..." and kExitInputError; any other exception is
/// "tumble COMMAND: internal error: ..." and kExitInternalError. `on_error`, called first
/// with nothing thrown out of it, may claim the failure instead (a render interrupted while
/// ffmpeg failed reports the interruption) by returning a status other than -1.
template <typename Body, typename OnError>
int run_guarded(std::string_view command, std::ostream& err, Body&& body, OnError&& on_error) {
  const auto report = [&](const char* kind, const std::exception& error, int status) {
    const int claimed = on_error();
    if (claimed != -1) return claimed;
    err << "tumble " << command << ": " << kind << error.what() << "\n";
    return status;
  };
  try {
    return body();
  } catch (const InputError& error) {
    return report("error: ", error, kExitInputError);
  } catch (const std::exception& error) {
    return report("internal error (a bug in tumble, please report it): ", error,
                  kExitInternalError);
  }
}

/// run_guarded with no claim on failures.
template <typename Body>
int run_guarded(std::string_view command, std::ostream& err, Body&& body) {
  return run_guarded(command, err, static_cast<Body&&>(body), [] { return -1; });
}

}  // namespace tumble::app
