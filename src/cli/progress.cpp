#include "cli/progress.h"

#include <fmt/format.h>

namespace coinroll::cli {

ProgressLine::ProgressLine(bool enabled)
    : enabled_(enabled), start_(std::chrono::steady_clock::now()), lastPrint_(start_) {}

void ProgressLine::update(long done, long total) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (done != total && now - lastPrint_ < std::chrono::milliseconds(200)) return;
  lastPrint_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double rate = elapsed > 0 ? done / elapsed : 0;
  const double remaining = rate > 0 ? (total - done) / rate : 0;
  fmt::print(stderr, "\rrender: frame {}/{} ({:3.0f} %), {:.1f} frames/s, {:.1f} s left   ", done, total,
             100.0 * done / total, rate, remaining);
  std::fflush(stderr);
  printed_ = true;
}

void ProgressLine::finish() {
  if (printed_) fmt::print(stderr, "\n");
  printed_ = false;
}

}  // namespace coinroll::cli
