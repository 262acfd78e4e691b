// tumble.InputError, numpy conversions and signal checks (python_support.hpp).
#include "python_support.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <system_error>
#include <vector>

#include "base/errors.hpp"

namespace tumble::python {
namespace {

/// tumble.InputError, once created.
PyObject* input_error_type = nullptr;

double seconds_now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// The text before a message's first ": ", or "".
std::string head_of(const std::string& message) {
  const std::size_t colon = message.find(": ");
  return colon == std::string::npos ? std::string() : message.substr(0, colon);
}

/// The file a one-line message names: its head when that is an existing path (a mesh a robot
/// file names); None when the message names an argument ("faces[3]: ...", "density: ...").
py::object file_of(const std::string& message) {
  const std::string head = head_of(message);
  std::error_code error;
  if (!head.empty() && std::filesystem::exists(head, error)) return py::str(head);
  return py::none();
}

void raise_input_error(const std::string& message, const py::object& file) {
  py::object error = py::reinterpret_borrow<py::object>(input_error_type)(message);
  error.attr("file") = file;
  PyErr_SetObject(input_error_type, error.ptr());
}

}  // namespace

void bind_input_error(py::module_& module) {
  static py::exception<tumble::InputError> type(module, "InputError", PyExc_ValueError);
  input_error_type = type.ptr();
  type.attr("__module__") = "tumble";
  type.doc() =
      "Bad input: a mesh, a scene, a robot file, an argument. str(error) is the command line's "
      "one-line message naming the file and the field; error.file is that file (None when the "
      "message names an argument).";
  py::register_exception_translator([](std::exception_ptr thrown) {
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const NamedInputError& error) {
      raise_input_error(error.what(), py::str(error.file));
    } catch (const tumble::InputError& error) {
      raise_input_error(error.what(), file_of(error.what()));
    }
  });
}

void rethrow_naming(const tumble::InputError& error, const std::vector<std::string>& paths) {
  const std::string head = head_of(error.what());
  if (std::find(paths.begin(), paths.end(), head) != paths.end()) {
    throw NamedInputError(error.what(), head);
  }
  throw error;
}

void throw_input_error(const std::string& message) {
  throw tumble::InputError(message);
}

py::array_t<double> to_numpy(const Eigen::Vector3d& v) {
  py::array_t<double> out(3);
  auto view = out.mutable_unchecked<1>();
  for (py::ssize_t i = 0; i < 3; ++i) view(i) = v(i);
  return out;
}

py::array_t<double> to_numpy(const Eigen::Matrix3d& m) {
  py::array_t<double> out({3, 3});
  auto view = out.mutable_unchecked<2>();
  for (py::ssize_t r = 0; r < 3; ++r) {
    for (py::ssize_t c = 0; c < 3; ++c) view(r, c) = m(r, c);
  }
  return out;
}

engine::OverlapMode overlap_mode_of(const std::optional<std::string>& overlap, bool allow_overlap) {
  if (!overlap) return allow_overlap ? engine::OverlapMode::kSum : engine::OverlapMode::kUnion;
  const auto mode = engine::overlap_mode_named(*overlap);
  if (!mode) {
    throw_input_error("overlap: expected 'union', 'sum' or 'refuse', got '" + *overlap + "'");
  }
  if (allow_overlap && *mode != engine::OverlapMode::kSum) {
    throw_input_error("allow_overlap: True is overlap='sum'; it contradicts overlap='" + *overlap +
                      "'");
  }
  return *mode;
}

Eigen::Vector3d vector3(const py::handle& value, const std::string& what) {
  py::array_t<double, py::array::c_style | py::array::forcecast> array;
  try {
    array = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value);
  } catch (const py::error_already_set&) {
    array = {};
  }
  if (!array || array.ndim() != 1 || array.shape(0) != 3) {
    throw_input_error(what + ": expected three numbers");
  }
  const Eigen::Vector3d v(array.at(0), array.at(1), array.at(2));
  if (!v.allFinite()) throw_input_error(what + ": expected three finite numbers");
  return v;
}

SignalCheck::SignalCheck() : next_check_(seconds_now() + 0.05) {}

bool SignalCheck::operator()() {
  if (interrupted_) return true;
  const double now = seconds_now();
  if (now < next_check_) return false;
  next_check_ = now + 0.05;
  py::gil_scoped_acquire gil;
  if (PyErr_CheckSignals() != 0) {
    PyObject *type = nullptr, *value = nullptr, *traceback = nullptr;
    PyErr_Fetch(&type, &value, &traceback);
    type_ = py::reinterpret_steal<py::object>(type);
    value_ = py::reinterpret_steal<py::object>(value);
    traceback_ = py::reinterpret_steal<py::object>(traceback);
    interrupted_ = true;
  }
  return interrupted_;
}

void SignalCheck::raise_if_interrupted() {
  if (!interrupted_) return;
  PyErr_Restore(type_.release().ptr(), value_.release().ptr(), traceback_.release().ptr());
  throw py::error_already_set();
}

}  // namespace tumble::python
