#pragma once
/// @file Comma-separated command-line lists (--integrators, --dts, --tolerances, --cases),
/// checked with one-line errors naming the option.

#include <string>
#include <vector>

#include "engine/dynamics/integrators.hpp"

namespace tumble::app {

/// "a, b,c" -> {"a", "b", "c"} (blanks trimmed). An empty list or an empty item is an error.
std::vector<std::string> split_option_list(const std::string& text, const char* option);

/// A list of positive finite numbers, in the order given.
std::vector<double> parse_positive_list(const std::string& text, const char* option);

/// The integrators a list names, in the order given, each once.
std::vector<const engine::IntegratorInfo*> parse_integrator_list(const std::string& text,
                                                                 const char* option);

}  // namespace tumble::app
