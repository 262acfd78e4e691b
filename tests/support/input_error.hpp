#pragma once
// The message of the tumble::InputError a call throws, for tests of error reporting.

#include <gtest/gtest.h>

#include <string>

#include "base/errors.hpp"

namespace tumble::testing {

/// The message of the tumble::InputError that `action()` throws. When it throws none, the test
/// fails (saying `what` was accepted) and the result is empty. Other exceptions propagate.
template <typename Action>
std::string input_error_of(Action&& action, const std::string& what = "the input") {
  try {
    action();
  } catch (const tumble::InputError& error) {
    return error.what();
  }
  ADD_FAILURE() << "no InputError: " << what << " was accepted";
  return {};
}

}  // namespace tumble::testing
