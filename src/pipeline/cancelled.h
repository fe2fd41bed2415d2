#pragma once
// Stopping a long computation on request (Ctrl-C): loops poll a flag the caller owns and unwind
// with Cancelled, so every partial output is removed by its owner on the way out.

#include <atomic>
#include <stdexcept>

namespace coinroll::pipeline {

class Cancelled : public std::runtime_error {
 public:
  Cancelled() : std::runtime_error("interrupted") {}
};

// Throws Cancelled when `flag` is set; a null flag never cancels.
inline void throwIfCancelled(const std::atomic<bool>* flag) {
  if (flag != nullptr && flag->load(std::memory_order_relaxed)) throw Cancelled();
}

}  // namespace coinroll::pipeline
