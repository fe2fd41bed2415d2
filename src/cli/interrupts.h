#pragma once
// What coinroll does on a signal, for the whole program (docs/signals_and_limits.md): installed by
// main() before any command creates an output, undone when the command is over. The libraries
// install no handler; they take the flag below as their cancellation token.
//
// - A request to stop: SIGINT, SIGTERM, SIGHUP, SIGQUIT and every other signal whose default
//   action ends the process (SIGALRM, SIGUSR1, SIGUSR2, SIGXCPU, SIGVTALRM, SIGPROF, SIGIO,
//   SIGPWR, SIGSTKFLT, the real-time signals) sets the flag. Every long loop polls it and unwinds
//   with pipeline::Cancelled; the outputs' owners remove their temporaries on the way, and the
//   command fails with interruptionMessage().
// - A second request, or the first one not obeyed within kStopGraceSeconds (the work is inside a
//   call that cannot poll: an OpenGL draw, the encoder, opening a FIFO nobody reads), ends the
//   process at once: every unfinished file goes (io::removeUnfinishedFiles), one line says so on
//   stderr, and the exit code is the command's failure code.
// - SIGPIPE (a reader went away) ends coinroll silently as before, like any Unix filter, after
//   removing the unfinished files.
// - SIGXFSZ (a file-size limit, `ulimit -f`) is ignored, so the write that passes the limit fails
//   with EFBIG and is reported as a full disk is, instead of killing the process.
// - A crash (SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGTRAP, SIGSYS) removes the unfinished
//   files, says so under an address-space limit (where it is most likely memory running out inside
//   a library), then crashes as before.
// A signal ignored when coinroll starts stays ignored (nohup; a background job of a shell without
// job control ignores SIGINT and SIGQUIT), and one that already has a handler keeps it (a
// sanitizer's, a profiler's). SIGALRM is always ours: the grace timer uses it.

#include <signal.h>

#include <atomic>
#include <string>
#include <utility>
#include <vector>

namespace coinroll::cli {

// s. Long enough for every loop to reach its next poll (a frame, a sample, a sweep point), short
// enough that a stuck library call does not keep the user waiting.
inline constexpr unsigned kStopGraceSeconds = 3;

class InterruptGuard {
 public:
  // `exitCodeWhenForced`: the exit code of a process ended at once (the command's failure code).
  explicit InterruptGuard(int exitCodeWhenForced);
  ~InterruptGuard();  // restores the previous handlers and stops the grace timer
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;

 private:
  std::vector<std::pair<int, struct sigaction>> previous_;  // the signals changed, as they were
};

// Set by the first request to stop since the guard was installed.
const std::atomic<bool>& interruptRequested();

// "interrupted by SIGTERM": which request set the flag.
std::string interruption();

// "interrupted by SIGTERM; nothing was written to OUTPUT", for a command whose loop stopped on
// the flag; a stream (OUTPUT "-", a device, a pipe) keeps what it was given before.
std::string interruptionMessage(const std::string& output);

}  // namespace coinroll::cli
