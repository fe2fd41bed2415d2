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
  // promise to allow (std::atomic_flag is always lock-free). Held only for a few system calls (a
  // commit: two per file).
  std::atomic_flag locked;
  std::vector<std::string> paths;       // "" = a free slot
  std::vector<std::size_t> freeSlots;
};
constinit UnfinishedFiles files;

// Sections open on this thread, and the signal mask the outermost one replaced.
thread_local int sectionDepth = 0;
thread_local sigset_t maskBeforeSection;

// sched_yield is a bare system call, so safe in a handler whatever POSIX's list says; the holder
// runs on another thread and needs the processor to finish.
void lock() noexcept {
  while (files.locked.test_and_set(std::memory_order_acquire)) ::sched_yield();
}

void unlock() noexcept { files.locked.clear(std::memory_order_release); }

}  // namespace

UnfinishedFilesSection::UnfinishedFilesSection() {
  if (sectionDepth++ > 0) return;
  sigset_t all;
  ::sigfillset(&all);
  ::pthread_sigmask(SIG_BLOCK, &all, &maskBeforeSection);
  lock();
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
  // This thread holds the lock only if it crashed inside a section (abort() unblocks SIGABRT):
  // the list may be half changed and waiting would never end, so nothing is removed.
  if (sectionDepth > 0) return;
  lock();
  for (const std::string& path : files.paths) {
    if (!path.empty()) ::unlink(path.c_str());
  }
}

std::size_t unfinishedFileCount() {
  const UnfinishedFilesSection section;
  return files.paths.size() - files.freeSlots.size();
}

}  // namespace coinroll::io
