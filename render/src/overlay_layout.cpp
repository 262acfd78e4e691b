#include "render/overlay_layout.hpp"

#include <algorithm>
#include <cmath>

namespace tumble::render {

float overlay_font_px(int width, int height, double font_scale) {
  const double relative =
      std::min(static_cast<double>(width) / 1280.0, static_cast<double>(height) / 720.0);
  const double px = std::round(kDefaultFontPx * relative * font_scale);
  return static_cast<float>(
      std::clamp(px, static_cast<double>(kMinFontPx), static_cast<double>(kMaxFontPx)));
}

float overlay_text_width(std::size_t chars, float font_px) {
  const float size = std::round(std::clamp(font_px, kMinFontPx, kMaxFontPx));
  return static_cast<float>(chars) * 7.0f * size / kDefaultFontPx;
}

float compact_panel_padding(float font_px) {
  return std::max(2.0f, std::round(0.2f * font_px));
}

float compact_panel_spacing(float font_px) {
  return std::max(1.0f, std::round(0.1f * font_px));
}

std::vector<std::size_t> min_max_decimation(const std::vector<float>& values, int buckets) {
  const std::size_t n = values.size();
  const auto columns = static_cast<std::size_t>(std::max(1, buckets));
  std::vector<std::size_t> kept;
  if (n <= 2 * columns) {
    for (std::size_t i = 0; i < n; ++i) kept.push_back(i);
    return kept;
  }
  for (std::size_t b = 0; b < columns; ++b) {
    const std::size_t first = n * b / columns;
    const std::size_t last = n * (b + 1) / columns;
    std::size_t lo = first;
    std::size_t hi = first;
    for (std::size_t i = first; i < last; ++i) {
      if (values[i] < values[lo]) lo = i;
      if (values[i] > values[hi]) hi = i;
    }
    kept.push_back(std::min(lo, hi));
    if (hi != lo) kept.push_back(std::max(lo, hi));
  }
  return kept;
}

}  // namespace tumble::render
