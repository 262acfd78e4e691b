#include "app/support/printf_number.hpp"

#include <cstdio>

namespace tumble::app {

std::string printf_number(double value, const char* format) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

}  // namespace tumble::app
