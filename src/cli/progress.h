#pragma once
// The progress line of long renders: frames, rate and time left, rewritten in place on a
// terminal, at most a few times per second so printing never costs frames.

#include <chrono>
#include <cstdio>

namespace coinroll::cli {

class ProgressLine {
 public:
  // Prints only when `enabled` (stderr is a terminal and --quiet was not given).
  explicit ProgressLine(bool enabled);
  void update(long done, long total);
  void finish();  // ends the line so later messages start on their own

 private:
  bool enabled_;
  bool printed_ = false;
  std::chrono::steady_clock::time_point start_, lastPrint_;
};

}  // namespace coinroll::cli
