// The unit hint of `tumble inspect` and `tumble inertials`: a body 111 m long was most likely
// drawn in millimetres.
#include "app/scene/unit_hint.hpp"

#include <array>
#include <cmath>
#include <cstdio>

namespace tumble::app {
namespace {

/// The range of sizes a hint aims for, in metres: a bolt to a car.
constexpr double kSmallest = 0.01;
constexpr double kLargest = 10.0;

/// Whether `length` (m) is a size a body is likely to have.
bool plausible(double length) {
  return length >= kSmallest && length <= kLargest;
}

struct Unit {
  const char* name;
  double factor;
};
constexpr std::array<Unit, 3> kHintUnits = {
    {{"millimetres", 0.001}, {"inches", 0.0254}, {"micrometres", 1e-6}}};

/// Four significant digits: "111", "2000", "0.0254", "1e-06".
std::string number(double value) {
  std::array<char, 32> text{};
  std::snprintf(text.data(), text.size(), "%.4g", value);
  return text.data();
}

}  // namespace

std::optional<std::string> unit_hint(const engine::MeshReport& report,
                                     const Eigen::Vector3d& scale) {
  const double length = (report.bounds_max - report.bounds_min).maxCoeff();
  if (!std::isfinite(length) || length <= 0.0) return std::nullopt;
  const bool unscaled = scale.cwiseAbs() == Eigen::Vector3d::Ones();
  if (length > kLargest && unscaled) {
    std::string hint;
    for (const Unit& unit : kHintUnits) {
      if (!plausible(length * unit.factor)) continue;
      hint +=
          std::string(hint.empty() ? "" : "; ") + unit.name + "? --scale " + number(unit.factor);
    }
    if (hint.empty()) return std::nullopt;
    return "size " + number(length) + " m: " + hint;
  }
  if (length < 0.001) {
    const std::string size = "size " + number(length * 1000.0) + " mm: ";
    if (unscaled) return size + "under a millimetre; if the file is not in metres, give --scale";
    const double file_length = length / scale.cwiseAbs().maxCoeff();
    if (plausible(file_length))
      return size + "the file may already be in metres: leave out --scale";
  }
  return std::nullopt;
}

std::optional<double> likely_unit_factor(const engine::MeshReport& report,
                                         const Eigen::Vector3d& scale) {
  const double length = (report.bounds_max - report.bounds_min).maxCoeff();
  if (!std::isfinite(length) || length <= kLargest) return std::nullopt;
  if (scale.cwiseAbs() != Eigen::Vector3d::Ones()) return std::nullopt;
  for (const Unit& unit : kHintUnits) {
    if (plausible(length * unit.factor)) return unit.factor;
  }
  return std::nullopt;
}

std::string unit_name(double factor) {
  for (const Unit& unit : kHintUnits) {
    if (unit.factor == factor) return unit.name;
  }
  return "units of " + number(factor) + " m";
}

}  // namespace tumble::app
