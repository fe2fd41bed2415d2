#pragma once
// SIGINT and SIGTERM for the whole program, installed by main() before any command creates an
// output: the first signal sets a flag that every long loop polls (it unwinds with
// pipeline::Cancelled, and the outputs' owners remove their temporary files on the way out); a
// second signal ends the process at once, for a user who does not want to wait.

#include <atomic>

namespace coinroll::cli {

class InterruptGuard {
 public:
  InterruptGuard();
  ~InterruptGuard();  // restores the previous handlers
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;

 private:
  void (*previousInt_)(int) = nullptr;
  void (*previousTerm_)(int) = nullptr;
};

// Set by the first SIGINT or SIGTERM since the guard was installed.
const std::atomic<bool>& interruptRequested();

}  // namespace coinroll::cli
