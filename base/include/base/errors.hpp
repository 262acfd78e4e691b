#pragma once
/// @file The one error type for bad input, shared by engine, render and app.
///
/// Every command maps what happened to one exit status (app/support/exit_status.hpp):
/// 0 done, 1 bad input (an InputError: one line naming the file and field), 3 the run blew up,
/// 130 interrupted, 70 internal error. Anything thrown that is not an InputError is a bug and
/// exits 70, never as "bad input".

#include <stdexcept>
#include <string>

namespace tumble {

/// An error in what the user gave us: a mesh, a scene field, an option, an output path that
/// cannot be written, a tool the output needs (ffmpeg) failing on it. Its message is one line
/// that names the source (file, field) and says what was expected. Thrown only at the edges
/// (loading, validating, opening outputs), never from the step loop.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace tumble
