#pragma once
/// @file Sizes of the overlay (text, panels, plots) derived from the frame, shared by the
/// renderer's ImGui pass and the app that lays panels out, plus the min/max decimation of long
/// series that keeps a plot's vertex count bounded by its width.

#include <cstddef>
#include <vector>

namespace tumble::render {

/// ImGui's default font (ProggyClean) is designed at 13 px; the overlay's spacings are scaled
/// by font_px / kDefaultFontPx.
inline constexpr float kDefaultFontPx = 13.0f;
/// Text is never drawn smaller than this (readability floor, also for small frames and
/// --font-scale below 1).
inline constexpr float kMinFontPx = 10.0f;
/// Upper limit of the text height (a 8192-pixel frame with font_scale 8 stays sane).
inline constexpr float kMaxFontPx = 160.0f;

/// Text height for a `width` x `height` frame: 13 px at 1280x720, proportional to the frame's
/// smaller relative side, times `font_scale`, rounded to whole pixels, within
/// [kMinFontPx, kMaxFontPx].
float overlay_font_px(int width, int height, double font_scale = 1.0);

/// Width in pixels of `chars` characters of the overlay font at `font_px`. The font is
/// monospaced, 7 px per character at 13 px, and rasterised at whole pixel sizes (font_px
/// rounded, within the limits above): 7 px * size / 13 a character (5.38 px at 10 px; ImGui
/// 1.86 keeps the fraction, so a line of n characters is n times that wide, measured in
/// tests/app/commands/compare_tile_coverage_test.cpp).
float overlay_text_width(std::size_t chars, float font_px);

/// A compact panel (OverlayPanel::compact, a corner label without a title bar) leaves this
/// many pixels between its edge and its text at `font_px`, on every side...
float compact_panel_padding(float font_px);
/// ... and this many between its lines.
float compact_panel_spacing(float font_px);

/// Indices of the samples to draw when `count` samples are shown in `buckets` pixel columns:
/// all of them when they fit (count <= 2 * buckets), otherwise each column's minimum and
/// maximum in the order they occur, so spikes survive and the vertex count stays <= 2 * buckets.
std::vector<std::size_t> min_max_decimation(const std::vector<float>& values, int buckets);

}  // namespace tumble::render
