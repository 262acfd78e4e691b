#pragma once
// The constants the exact solutions' sources share (private to engine/exact).

#include <limits>
#include <numbers>

namespace tumble::engine::exact_numbers {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
inline constexpr double kInf = std::numeric_limits<double>::infinity();

}  // namespace tumble::engine::exact_numbers
