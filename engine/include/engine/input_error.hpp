#pragma once
/// @file Errors in what the user gave us: files, fields, values.

#include <stdexcept>
#include <string>

namespace tumble::engine {

/// An error in the user's input (a mesh, a scene field, a value). Its message is one line that
/// names the source (file, field) and says what was expected; the app prints it and exits
/// non-zero. Thrown only at the edges (loading, validating), never from the step loop.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace tumble::engine
