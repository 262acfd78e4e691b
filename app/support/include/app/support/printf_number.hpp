#pragma once
/// @file Numbers in messages and reports, printed the way printf prints them.

#include <string>

namespace tumble::app {

/// `value` as printf prints it with `format`, which holds exactly one double conversion
/// ("%.6g", "%.9g", "%.2f"...). Locale-independent only as far as printf is in the C locale,
/// which tumble never changes.
std::string printf_number(double value, const char* format = "%.6g");

}  // namespace tumble::app
