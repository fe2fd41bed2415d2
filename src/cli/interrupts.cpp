#include "cli/interrupts.h"

#include <fmt/format.h>

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <initializer_list>

#include "io/destination.h"
#include "io/unfinished_files.h"
#include "pipeline/resources.h"

namespace coinroll::cli {

namespace {

// What the handlers read. A handler can reach only what is global; each of these is set before
// the handlers are installed, or is a lock-free atomic, so reading it there is async-signal-safe.
std::atomic<bool> requested{false};
std::atomic<int> firstRequest{0};  // the first request's signal; 0 before it
static_assert(std::atomic<bool>::is_always_lock_free && std::atomic<int>::is_always_lock_free);
int exitCodeWhenForced = 1;
// Under an address-space limit, the end of the line a crash prints (empty without a limit).
char crashNote[256] = "";

constexpr std::initializer_list<int> kStopSignals = {SIGHUP,  SIGINT,    SIGQUIT, SIGTERM, SIGUSR1, SIGUSR2,
                                                     SIGXCPU, SIGVTALRM, SIGPROF, SIGIO,   SIGPWR,  SIGSTKFLT};
constexpr std::initializer_list<int> kCrashSignals = {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGTRAP, SIGSYS};

// A name from static storage, so a handler can print it.
const char* signalName(int signal) noexcept {
  switch (signal) {
    case SIGHUP: return "SIGHUP";
    case SIGINT: return "SIGINT";
    case SIGQUIT: return "SIGQUIT";
    case SIGTERM: return "SIGTERM";
    case SIGALRM: return "SIGALRM";
    case SIGUSR1: return "SIGUSR1";
    case SIGUSR2: return "SIGUSR2";
    case SIGXCPU: return "SIGXCPU (the CPU-time limit, ulimit -t)";
    case SIGVTALRM: return "SIGVTALRM";
    case SIGPROF: return "SIGPROF";
    case SIGIO: return "SIGIO";
    case SIGPWR: return "SIGPWR";
    case SIGSTKFLT: return "SIGSTKFLT";
    case SIGSEGV: return "SIGSEGV";
    case SIGBUS: return "SIGBUS";
    case SIGFPE: return "SIGFPE";
    case SIGILL: return "SIGILL";
    case SIGABRT: return "SIGABRT";
    case SIGTRAP: return "SIGTRAP";
    case SIGSYS: return "SIGSYS";
    default: return "a real-time signal";
  }
}

void say(const char* text) noexcept {
  [[maybe_unused]] const ssize_t written = ::write(STDERR_FILENO, text, std::strlen(text));
}

// The second request, or the grace timer's SIGALRM after the first: no loop will notice in time,
// so the process ends here. Only async-signal-safe calls from here on.
[[noreturn]] void endNow(int signal) noexcept {
  io::removeUnfinishedFiles();
  // Standard error may be a pipe whose reader is gone: the line below is then lost, and the write
  // fails with EPIPE instead of raising SIGPIPE, so the exit code stays the command's failure code
  // rather than a death by SIGPIPE inside this handler.
  struct sigaction ignore {};
  ignore.sa_handler = SIG_IGN;
  ::sigemptyset(&ignore.sa_mask);
  ::sigaction(SIGPIPE, &ignore, nullptr);
  const int first = firstRequest.load();
  say("coinroll: error: interrupted by ");
  say(signalName(first));
  if (signal == SIGALRM && first != SIGALRM) {
    const char seconds[] = {static_cast<char>('0' + kStopGraceSeconds), '\0'};
    static_assert(kStopGraceSeconds < 10);
    say(" and not stopped within ");
    say(seconds);
    say(" s (inside a call that cannot stop half-way)");
  } else if (signal == first) {
    say(" twice");
  } else {
    say(", then ");
    say(signalName(signal));
  }
  say(": stopped at once; no unfinished file is left\n");
  ::_exit(exitCodeWhenForced);
}

extern "C" void onStopRequest(int signal) {
  const int savedErrno = errno;
  int none = 0;
  if (!firstRequest.compare_exchange_strong(none, signal)) endNow(signal);
  requested.store(true);
  ::alarm(kStopGraceSeconds);
  errno = savedErrno;
}

// Installed with SA_RESETHAND: the default action (end silently) is back once we are here.
extern "C" void onBrokenPipe(int signal) {
  io::removeUnfinishedFiles();
  ::raise(signal);
}

// Installed with SA_RESETHAND, so the default action (a core dump, a sanitizer's report) is back
// once we are here: a fault returns to the faulting instruction and crashes on it; a signal that
// was sent (kill, abort) is sent again.
extern "C" void onCrash(int signal, siginfo_t* info, void*) {
  io::removeUnfinishedFiles();
  if (crashNote[0] != '\0' && info->si_code != SI_USER) {  // not for a signal someone sent with kill
    say("coinroll: error: crashed (");
    say(signalName(signal));
    say(crashNote);
  }
  if (info->si_code <= 0) ::raise(signal);
}

}  // namespace

InterruptGuard::InterruptGuard(int exitCode) {
  requested.store(false);
  firstRequest.store(0);
  exitCodeWhenForced = exitCode;
  crashNote[0] = '\0';
  if (const std::optional<std::uint64_t> limit = pipeline::addressSpaceLimit()) {
    std::snprintf(crashNote, sizeof crashNote,
                  ") under %s: most likely memory ran out inside a library (OpenGL, "
                  "the encoder); raise the limit\n",
                  pipeline::memoryLimitDescription().c_str());
  }

  // Installs `action` for `signal` if the signal is at its default action (or `always`), keeping
  // what was there for the destructor.
  const auto install = [this](int signal, const struct sigaction& action, bool always) {
    struct sigaction before {};
    if (::sigaction(signal, nullptr, &before) != 0) return;
    const bool isDefault = (before.sa_flags & SA_SIGINFO) == 0 && before.sa_handler == SIG_DFL;
    if (!always && !isDefault) return;  // ignored, or someone else's
    if (::sigaction(signal, &action, nullptr) == 0) previous_.emplace_back(signal, before);
  };
  const auto actionOf = [](void (*handler)(int), int flags) {
    struct sigaction action {};
    action.sa_handler = handler;
    action.sa_flags = flags;
    ::sigemptyset(&action.sa_mask);
    return action;
  };
  // SA_RESTART: a read or write the signal interrupts goes on, and the loop around it sees the flag.
  const struct sigaction stop = actionOf(onStopRequest, SA_RESTART);
  for (const int signal : kStopSignals) install(signal, stop, false);
  for (int signal = SIGRTMIN; signal <= SIGRTMAX; ++signal) install(signal, stop, false);
  install(SIGALRM, stop, true);
  install(SIGPIPE, actionOf(onBrokenPipe, SA_RESETHAND), false);
  install(SIGXFSZ, actionOf(SIG_IGN, 0), false);
  struct sigaction crash = actionOf(nullptr, SA_SIGINFO | SA_RESETHAND);
  crash.sa_sigaction = onCrash;
  for (const int signal : kCrashSignals) install(signal, crash, false);
}

InterruptGuard::~InterruptGuard() {
  ::alarm(0);
  // After a stop request the process is on its way out; with the default action back, a second
  // signal in that window would kill it outright instead of ending it as endNow says (a second
  // SIGINT 2 ms after the first, during a render that stopped within them).
  if (firstRequest.load() != 0) return;
  for (auto entry = previous_.rbegin(); entry != previous_.rend(); ++entry)
    ::sigaction(entry->first, &entry->second, nullptr);
}

const std::atomic<bool>& interruptRequested() { return requested; }

std::string interruption() {
  const int signal = firstRequest.load();
  if (signal >= SIGRTMIN && signal <= SIGRTMAX) return fmt::format("interrupted by SIGRTMIN+{}", signal - SIGRTMIN);
  return fmt::format("interrupted by {}", signalName(signal));
}

std::string interruptionMessage(const std::string& output) {
  if (output == "-") return interruption() + "; standard output keeps what it was given before";
  if (io::namesStream(output)) return fmt::format("{}; {} keeps what it was given before", interruption(), output);
  return fmt::format("{}; nothing was written to {}", interruption(), output);
}

}  // namespace coinroll::cli
