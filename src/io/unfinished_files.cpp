#include "io/unfinished_files.h"

#include <pthread.h>
#include <sched.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <string>
#include <vector>

namespace coinroll::io {

namespace {

// The process's list (see the header for why it is not an object's). Constant-initialized, so a
// handler that runs before anything was listed finds it ready, with no guard of a function-local
// static to race.
struct UnfinishedFiles {
  // A spin lock rather than a mutex: a signal handler may take it, which std::mutex does not
  // promise to allow (a lock-free atomic). Held only for a few system calls (a commit: two per
  // file), or for good by a removal. It holds the holder's thread id, not a flag: a handler that
  // interrupts a removal on its own thread (SIGPIPE raised by the forced end's message to a dead
  // stderr, a second stop during a broken pipe's removal) must see that the lock is its thread's,
  // since waiting for it would spin for ever (docs/signals_and_limits.md "The staging area a
  // handler can remove"). Taken by one compare-exchange, so no signal can land between taking the
  // lock and saying whose it is.
  std::atomic<pid_t> holder{0};    // 0: free
  std::vector<std::string> paths;  // "" = a free slot
  std::vector<std::size_t> freeSlots;
};
static_assert(std::atomic<pid_t>::is_always_lock_free);
constinit UnfinishedFiles files;

// Sections open on this thread, and the signal mask the outermost one replaced.
thread_local int sectionDepth = 0;
thread_local sigset_t maskBeforeSection;

// gettid and sched_yield are bare system calls, so safe in a handler whatever POSIX's list says;
// the holder runs on another thread and needs the processor to finish. A removal (`reentrant`)
// returns at once when this thread holds the lock already; a section never does, so that a file is
// never listed or published on the thread of a removal that left the lock held for good, and the
// section's end never releases that hold.
void lock(bool reentrant) noexcept {
  const pid_t self = ::gettid();
  pid_t expected = 0;
  while (!files.holder.compare_exchange_weak(expected, self, std::memory_order_acquire)) {
    if (reentrant && expected == self) return;
    expected = 0;
    ::sched_yield();
  }
}

void unlock() noexcept { files.holder.store(0, std::memory_order_release); }

}  // namespace

UnfinishedFilesSection::UnfinishedFilesSection() {
  if (sectionDepth++ > 0) return;
  sigset_t all;
  ::sigfillset(&all);
  ::pthread_sigmask(SIG_BLOCK, &all, &maskBeforeSection);
  lock(false);
}

UnfinishedFilesSection::~UnfinishedFilesSection() {
  if (--sectionDepth > 0) return;
  unlock();
  ::pthread_sigmask(SIG_SETMASK, &maskBeforeSection, nullptr);
}

ListedFile UnfinishedFilesSection::list(const std::filesystem::path& path) const {
  if (files.freeSlots.empty()) {
    files.paths.push_back(path.string());
    return ListedFile(files.paths.size() - 1);
  }
  const std::size_t slot = files.freeSlots.back();
  files.freeSlots.pop_back();
  files.paths[slot] = path.string();
  return ListedFile(slot);
}

ListedFile& ListedFile::operator=(ListedFile&& other) noexcept {
  if (this != &other) {
    reset();
    slot_ = other.slot_;
    other.slot_ = kNone;
  }
  return *this;
}

void ListedFile::reset() noexcept {
  if (slot_ == kNone) return;
  const UnfinishedFilesSection section;
  std::string().swap(files.paths[slot_]);  // frees it: a long sequence's names do not pile up
  try {
    files.freeSlots.push_back(slot_);
  } catch (...) {
    // Out of memory: the slot stays empty and unused, which only wastes it.
  }
  slot_ = kNone;
}

void removeUnfinishedFiles() noexcept {
  // Inside a section only if this thread crashed there (abort() unblocks SIGABRT): the list may be
  // half changed, so nothing is removed.
  if (sectionDepth > 0) return;
  // Outside a section, a lock this thread already holds was taken by a removal this call
  // interrupts, or one that ran before it: the list is locked against every change, so it is
  // read again (unlinking a removed file again only fails) instead of waited for.
  lock(true);
  for (const std::string& path : files.paths) {
    if (!path.empty()) ::unlink(path.c_str());
  }
}

std::size_t unfinishedFileCount() {
  const UnfinishedFilesSection section;
  return files.paths.size() - files.freeSlots.size();
}

}  // namespace coinroll::io
