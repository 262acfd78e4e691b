#pragma once
/// @file Ctrl-C and SIGTERM turned into a flag that a long loop polls, so it can stop cleanly
/// (outputs removed, one line said) instead of dying mid-write.

#include <signal.h>

#include <ostream>
#include <string>
#include <string_view>

namespace tumble::app {

/// Catches SIGINT and SIGTERM for its lifetime and remembers that one came, for a frame loop to
/// poll. A signal that was ignored when it was made (a background job's SIGINT) stays ignored; a
/// second signal stops the process at once.
class InterruptGuard {
 public:
  InterruptGuard();
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;

  bool interrupted() const;
  const char* signal_name() const;
  /// Writes the one line of an interrupted command, "tumble COMMAND: interrupted by SIGINT;
  /// nothing written to 'OUTPUT'" (without the clause when `output` is empty).
  void report(std::ostream& err, std::string_view command, const std::string& output) const;

 private:
  static void install(int signal, struct sigaction& old, bool& installed);

  struct sigaction old_interrupt_ {};
  struct sigaction old_terminate_ {};
  bool interrupt_installed_ = false;
  bool terminate_installed_ = false;
};

}  // namespace tumble::app
