#pragma once
// What every binding of the Python module shares: tumble.InputError (a ValueError carrying the
// command line's one-line message and the file it names), numpy arrays to and from Eigen, and
// the way long calls give the interpreter its signals back (Ctrl-C) without installing any
// handler of their own.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "base/errors.hpp"
#include "engine/mass/mesh_analysis.hpp"

namespace tumble::python {

namespace py = pybind11;

/// Creates tumble.InputError in `module` and translates tumble::InputError into it: the
/// message word for word, and `file`, the path the message starts with (None when it names an
/// option or an argument rather than a file).
void bind_input_error(py::module_& module);

/// An InputError about a file the call was given (which may not exist): tumble.InputError's
/// `file` is that path.
struct NamedInputError : tumble::InputError {
  NamedInputError(const std::string& message, std::string path)
      : tumble::InputError(message), file(std::move(path)) {}
  std::string file;
};

/// Throws `error` again, as a NamedInputError when its message starts with one of `paths`.
[[noreturn]] void rethrow_naming(const tumble::InputError& error,
                                 const std::vector<std::string>& paths);

/// Runs `call`; an InputError it throws that names one of `paths` carries that path as `file`.
template <typename Call>
auto naming_files(const std::vector<std::string>& paths, Call&& call) {
  try {
    return call();
  } catch (const NamedInputError&) {
    throw;
  } catch (const tumble::InputError& error) {
    rethrow_naming(error, paths);
  }
}

/// Raises tumble.InputError with `message` (from a binding's own checks of its arguments).
[[noreturn]] void throw_input_error(const std::string& message);

/// The overlap mode of the keywords `overlap` ("union", "sum" or "refuse"; default union) and
/// its old alias `allow_overlap` (True: "sum"); InputError when they disagree or the name is
/// unknown.
engine::OverlapMode overlap_mode_of(const std::optional<std::string>& overlap, bool allow_overlap);

/// A (3,) float64 array copied from `v`.
py::array_t<double> to_numpy(const Eigen::Vector3d& v);
/// A (3, 3) float64 array copied from `m` (row r of the array is row r of the matrix).
py::array_t<double> to_numpy(const Eigen::Matrix3d& m);

/// A 3-vector from a sequence or array of three finite numbers; InputError naming `what`.
Eigen::Vector3d vector3(const py::handle& value, const std::string& what);

/// A cancel predicate for library loops that run with the GIL released: every call at most
/// every 50 ms takes the GIL, runs the interpreter's pending signal handlers
/// (PyErr_CheckSignals) and answers true once one raised (KeyboardInterrupt from Ctrl-C).
/// After the call, `raise_if_interrupted` re-raises that exception in Python.
class SignalCheck {
 public:
  SignalCheck();
  /// True once a signal handler raised; safe to call without the GIL.
  bool operator()();
  /// With the GIL held: restores and raises the exception a handler raised, if any.
  void raise_if_interrupted();

 private:
  double next_check_ = 0.0;
  bool interrupted_ = false;
  py::object type_, value_, traceback_;
};

}  // namespace tumble::python
