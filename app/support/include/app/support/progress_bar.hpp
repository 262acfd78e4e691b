#pragma once
// A one-line progress bar for long jobs on a terminal: count, rate and time left.

#include <chrono>
#include <cstddef>
#include <iosfwd>
#include <string>

namespace tumble::app {

/// Redraws one line in place ("\r", then erase to the end of the line), at most ten times a
/// second. A disabled bar prints nothing; enable it where on_terminal() says so.
class ProgressBar {
 public:
  /// Whether `out` is the process's standard error and that is a terminal: where a bar that
  /// redraws its line can be seen (a log file or a pipe would collect every redraw).
  static bool on_terminal(const std::ostream& out);

  /// `unit` names what is counted ("frames"); `total` is the count at 100 %.
  ProgressBar(std::ostream& out, std::size_t total, std::string unit, bool enabled);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  /// Reports `done` items finished (redraws when due, and always at 100 %).
  void update(std::size_t done);

  /// Erases the bar, so that a message can take the line.
  void clear();

  /// The bar's text for `done` items after `seconds` (exposed for tests).
  static std::string line(std::size_t done, std::size_t total, const std::string& unit,
                          double seconds);

 private:
  std::ostream& out_;
  std::size_t total_;
  std::string unit_;
  bool enabled_;
  bool shown_ = false;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
};

}  // namespace tumble::app
