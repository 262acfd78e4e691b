#include "app/support/progress_bar.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <ostream>
#include <utility>

namespace tumble::app {
namespace {

constexpr auto kRedrawInterval = std::chrono::milliseconds(100);
constexpr std::size_t kBarWidth = 28;

/// "m:ss", or "h:mm:ss" from an hour.
std::string clock_text(double seconds) {
  const auto whole = static_cast<long long>(std::llround(std::max(seconds, 0.0)));
  char text[32];
  if (whole >= 3600) {
    std::snprintf(text, sizeof text, "%lld:%02lld:%02lld", whole / 3600, whole / 60 % 60,
                  whole % 60);
  } else {
    std::snprintf(text, sizeof text, "%lld:%02lld", whole / 60, whole % 60);
  }
  return text;
}

}  // namespace

bool ProgressBar::on_terminal(const std::ostream& out) {
  return &out == &std::cerr && ::isatty(STDERR_FILENO) == 1;
}

ProgressBar::ProgressBar(std::ostream& out, std::size_t total, std::string unit, bool enabled)
    : out_(out),
      total_(total),
      unit_(std::move(unit)),
      enabled_(enabled),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_ - kRedrawInterval) {}

ProgressBar::~ProgressBar() {
  clear();
}

std::string ProgressBar::line(std::size_t done, std::size_t total, const std::string& unit,
                              double seconds) {
  const double fraction =
      total > 0 ? std::min(1.0, static_cast<double>(done) / static_cast<double>(total)) : 1.0;
  const auto filled = static_cast<std::size_t>(fraction * static_cast<double>(kBarWidth));
  std::string bar(filled, '#');
  bar.resize(kBarWidth, '-');
  const double rate = seconds > 0.0 ? static_cast<double>(done) / seconds : 0.0;
  char text[160];
  std::snprintf(text, sizeof text, "[%s] %zu/%zu %s  %.1f %s/s  ", bar.c_str(), done, total,
                unit.c_str(), rate, unit.c_str());
  std::string out = text;
  if (done >= total) {
    out += "done in " + clock_text(seconds);
  } else if (rate > 0.0) {
    out += "ETA " + clock_text(static_cast<double>(total - done) / rate);
  } else {
    out += "ETA --:--";
  }
  return out;
}

void ProgressBar::update(std::size_t done) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (now - last_draw_ < kRedrawInterval && done < total_) return;
  last_draw_ = now;
  const double seconds = std::chrono::duration<double>(now - start_).count();
  out_ << '\r' << line(done, total_, unit_, seconds) << "\033[K" << std::flush;
  shown_ = true;
}

void ProgressBar::clear() {
  if (!shown_) return;
  out_ << "\r\033[K" << std::flush;
  shown_ = false;
}

}  // namespace tumble::app
