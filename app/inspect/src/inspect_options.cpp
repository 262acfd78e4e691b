// `--scale`'s factors.
#include "app/inspect/inspect_options.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "base/errors.hpp"

namespace tumble::app {

Eigen::Vector3d parse_scale_factors(const std::string& text) {
  const auto refuse = [&] {
    return tumble::InputError(
        "--scale: expected one factor or three (sx,sy,sz), each finite "
        "and non-zero, got \"" +
        text + "\"");
  };
  std::vector<double> factors;
  std::size_t begin = 0;
  while (true) {
    const std::size_t end = std::min(text.find(',', begin), text.size());
    double value = 0.0;
    const char* first = text.data() + begin;
    const char* last = text.data() + end;
    if (first != last && *first == '+') ++first;  // from_chars takes no '+'
    const auto [ptr, ec] = std::from_chars(first, last, value);
    if (ec != std::errc() || ptr != last || !std::isfinite(value) || value == 0.0) throw refuse();
    factors.push_back(value);
    if (end == text.size()) break;
    begin = end + 1;
  }
  if (factors.size() == 1) return Eigen::Vector3d::Constant(factors[0]);
  if (factors.size() == 3) return {factors[0], factors[1], factors[2]};
  throw refuse();
}

}  // namespace tumble::app
