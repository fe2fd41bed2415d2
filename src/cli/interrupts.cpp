#include "cli/interrupts.h"

#include <csignal>

namespace coinroll::cli {

namespace {

// Lock-free, so setting it is async-signal-safe.
std::atomic<bool> requested{false};
static_assert(std::atomic<bool>::is_always_lock_free);

extern "C" void onInterrupt(int signal) {
  if (requested.exchange(true)) {
    // The second signal: default action (terminate) at once.
    std::signal(signal, SIG_DFL);
    std::raise(signal);
  }
}

}  // namespace

InterruptGuard::InterruptGuard() {
  requested.store(false);
  previousInt_ = std::signal(SIGINT, onInterrupt);
  previousTerm_ = std::signal(SIGTERM, onInterrupt);
}

InterruptGuard::~InterruptGuard() {
  std::signal(SIGINT, previousInt_);
  std::signal(SIGTERM, previousTerm_);
}

const std::atomic<bool>& interruptRequested() { return requested; }

}  // namespace coinroll::cli
