#pragma once
/// @file The engine's name for tumble's one bad-input error (tumble/errors.hpp).

#include "tumble/errors.hpp"

namespace tumble::engine {

/// Errors in the user's input: the same type engine, render and app throw and catch.
using InputError = tumble::InputError;

}  // namespace tumble::engine
