#include "cli/progress.h"

#include <fmt/format.h>
#include <unistd.h>

#include <utility>

namespace coinroll::cli {

namespace {

// A log gets a line per tenth of the work, so a short job's log stays short, and one at least this
// often, so a slow job still shows that it is alive and how far it got.
constexpr long kLogSteps = 10;
constexpr auto kLogInterval = std::chrono::seconds(30);

// Seconds as a person reads them in a log: "4.2 s", "42 s", "12.5 min", "3.1 h".
std::string readableDuration(double seconds) {
  if (seconds < 10) return fmt::format("{:.1f} s", seconds);
  if (seconds < 100) return fmt::format("{:.0f} s", seconds);
  if (seconds < 6000) return fmt::format("{:.1f} min", seconds / 60);
  return fmt::format("{:.1f} h", seconds / 3600);
}

}  // namespace

ProgressLine::Style ProgressLine::styleFor(bool quiet) {
  if (quiet) return Style::Off;
  return isatty(STDERR_FILENO) == 1 ? Style::Terminal : Style::Log;
}

ProgressLine::Style ProgressLine::terminalStyleFor(bool quiet) {
  return styleFor(quiet) == Style::Terminal ? Style::Terminal : Style::Off;
}

ProgressLine::ProgressLine(Style style, std::string task, std::string unit)
    : style_(style),
      task_(std::move(task)),
      unit_(std::move(unit)),
      start_(std::chrono::steady_clock::now()),
      lastPrint_(start_) {}

void ProgressLine::update(long done, long total) {
  if (style_ == Style::Off || total <= 0) return;
  const auto now = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double rate = elapsed > 0 ? done / elapsed : 0;
  if (style_ == Style::Log) {
    const bool nextStep = done * kLogSteps / total > lastDone_ * kLogSteps / total;
    if (done == total || nextStep || now - lastPrint_ >= kLogInterval) {
      lastPrint_ = now;
      lastDone_ = done;
      printLog(done, total, elapsed, rate);
    }
    return;
  }
  if (done != total && now - lastPrint_ < std::chrono::milliseconds(200)) return;
  lastPrint_ = now;
  const double remaining = rate > 0 ? (total - done) / rate : 0;
  fmt::print(stderr, "\r{}: {} {}/{} ({:3.0f} %), {:.1f} {}s/s, {:.1f} s left   ", task_, unit_, done, total,
             100.0 * done / total, rate, unit_, remaining);
  std::fflush(stderr);
  printed_ = true;
}

void ProgressLine::printLog(long done, long total, double elapsed, double rate) {
  const std::string left = done == total ? "done"
                           : rate > 0    ? fmt::format("about {} left", readableDuration((total - done) / rate))
                                         : "time left unknown";
  fmt::print(stderr, "coinroll: {}: {}/{} {}s ({:.0f} %) after {}, {:.1f} {}s/s, {}\n", task_, done, total, unit_,
             100.0 * done / total, readableDuration(elapsed), rate, unit_, left);
  std::fflush(stderr);
}

void ProgressLine::finish() {
  if (printed_) fmt::print(stderr, "\n");
  printed_ = false;
}

}  // namespace coinroll::cli
