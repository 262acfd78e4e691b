#pragma once
// Comparing rendered images in tests: how many pixels differ, and by how much on average.

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdlib>
#include <optional>

#include "base/image.hpp"

namespace tumble::testing {

/// A pixel rectangle [x0, x1) x [y0, y1).
struct PixelRegion {
  int x0 = 0;
  int y0 = 0;
  int x1 = 0;
  int y1 = 0;
};

/// Pixels (of `region`, or the whole image) whose RGB differ by more than `levels` in some
/// channel. Images of different sizes fail the test and differ everywhere.
inline std::size_t pixels_differing(const tumble::Image& a, const tumble::Image& b, int levels = 0,
                                    std::optional<PixelRegion> region = std::nullopt) {
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  if (a.width != b.width || a.height != b.height || a.rgba.size() != b.rgba.size()) {
    return a.rgba.size() / 4;
  }
  const PixelRegion r = region.value_or(PixelRegion{0, 0, a.width, a.height});
  std::size_t count = 0;
  for (int y = r.y0; y < r.y1; ++y) {
    for (int x = r.x0; x < r.x1; ++x) {
      const std::size_t i = 4 * (static_cast<std::size_t>(y) * a.width + x);
      bool differs = false;
      for (std::size_t c = 0; c < 3; ++c) {
        differs = differs || std::abs(int{a.rgba[i + c]} - int{b.rgba[i + c]}) > levels;
      }
      count += differs ? 1 : 0;
    }
  }
  return count;
}

/// The fraction of all pixels that pixels_differing counts (1 for images of different sizes).
inline double fraction_differing(const tumble::Image& a, const tumble::Image& b, int levels) {
  if (a.rgba.empty()) return 1.0;
  return static_cast<double>(pixels_differing(a, b, levels)) /
         static_cast<double>(a.rgba.size() / 4);
}

/// Mean absolute difference per RGB channel, in 8-bit levels (different sizes fail the test
/// and give 255).
inline double mean_difference(const tumble::Image& a, const tumble::Image& b) {
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  if (a.width != b.width || a.height != b.height || a.rgba.size() != b.rgba.size()) return 255.0;
  double sum = 0.0;
  for (std::size_t i = 0; i < a.rgba.size(); ++i) {
    if (i % 4 != 3) sum += std::abs(int{a.rgba[i]} - int{b.rgba[i]});
  }
  return sum / (0.75 * static_cast<double>(a.rgba.size()));
}

}  // namespace tumble::testing
