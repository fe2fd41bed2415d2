#pragma once
// Progress of long work (a render's frames, a sweep's points) on stderr: on a terminal one line
// rewritten in place at most five times a second, so printing costs nothing beside the work; in a
// log (a batch job's output file, where a rewritten line piles up as one endless line) a line of
// its own at every tenth of the work and at least every 30 s.

#include <chrono>
#include <cstdio>
#include <string>

namespace coinroll::cli {

class ProgressLine {
 public:
  enum class Style { Off, Terminal, Log };

  // Off with --quiet, Terminal when stderr is a terminal, else Log.
  static Style styleFor(bool quiet);
  // As styleFor, but Off instead of Log: for work whose log keeps to its summary line (a render).
  static Style terminalStyleFor(bool quiet);

  // `task` and `unit` name the work in the line: "render", "frame"; "sweep shard 3/8", "point".
  ProgressLine(Style style, std::string task, std::string unit);
  void update(long done, long total);
  void finish();  // ends the line so later messages start on their own

 private:
  void printLog(long done, long total, double elapsed, double rate);

  Style style_;
  std::string task_, unit_;
  bool printed_ = false;
  long lastDone_ = 0;
  std::chrono::steady_clock::time_point start_, lastPrint_;
};

}  // namespace coinroll::cli
