#include "app/support/interrupt_guard.hpp"

#include <csignal>

namespace tumble::app {
namespace {

// SIGINT and SIGTERM set a flag that the frame loop polls: the loop stops, the sink is
// destroyed unfinished (its temporary removed) and the command returns kExitInterrupted.
volatile std::sig_atomic_t interrupt_signal = 0;

void on_interrupt(int signal) {
  interrupt_signal = signal;
}

}  // namespace

InterruptGuard::InterruptGuard() {
  interrupt_signal = 0;
  install(SIGINT, old_interrupt_, interrupt_installed_);
  install(SIGTERM, old_terminate_, terminate_installed_);
}

InterruptGuard::~InterruptGuard() {
  if (interrupt_installed_) sigaction(SIGINT, &old_interrupt_, nullptr);
  if (terminate_installed_) sigaction(SIGTERM, &old_terminate_, nullptr);
}

bool InterruptGuard::interrupted() const {
  return interrupt_signal != 0;
}

const char* InterruptGuard::signal_name() const {
  return interrupt_signal == SIGTERM ? "SIGTERM" : "SIGINT";
}

void InterruptGuard::report(std::ostream& err, std::string_view command,
                            const std::string& output) const {
  err << "tumble " << command << ": interrupted by " << signal_name();
  if (!output.empty()) err << "; nothing written to '" << output << "'";
  err << "\n";
}

void InterruptGuard::install(int signal, struct sigaction& old, bool& installed) {
  if (sigaction(signal, nullptr, &old) != 0 || old.sa_handler == SIG_IGN) return;
  struct sigaction action {};
  action.sa_handler = on_interrupt;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART | SA_RESETHAND;
  installed = sigaction(signal, &action, nullptr) == 0;
}

}  // namespace tumble::app
