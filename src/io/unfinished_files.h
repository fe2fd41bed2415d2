#pragma once
// The files the output layer has made and not yet published: the temporary an output is written
// under, a scratch file in $TMPDIR, an earlier file a PNG sequence keeps aside while it commits.
// Each is listed from just before it is created until it is renamed into place or removed, so a
// process that must end at once (a second Ctrl-C, a crash) can remove them all from a signal
// handler: removeUnfinishedFiles() is async-signal-safe. The io library installs no handler; the
// program decides when to call it (cli/interrupts.h).
//
// The list belongs to the process, not to an object, because a signal handler can reach nothing
// else. Every change to it happens inside an UnfinishedFilesSection, which blocks the calling
// thread's signals and takes a lock, so a handler never sees the list half changed and never
// waits for a lock its own thread holds: on another thread it waits for the section to end, and
// inside a removal on its own thread (a handler run inside another) it does not wait at all.

#include <cstddef>
#include <filesystem>

namespace coinroll::io {

// One listed file, from list() to its destruction (or reset()), which takes it off the list; the
// file itself is the owner's to rename or remove. Move-only; default-constructed, it lists nothing.
class ListedFile {
 public:
  ListedFile() = default;
  ~ListedFile() { reset(); }
  ListedFile(ListedFile&& other) noexcept : slot_(other.slot_) { other.slot_ = kNone; }
  ListedFile& operator=(ListedFile&& other) noexcept;
  ListedFile(const ListedFile&) = delete;
  ListedFile& operator=(const ListedFile&) = delete;

  // Takes the file off the list (it was published or removed).
  void reset() noexcept;

 private:
  friend class UnfinishedFilesSection;
  static constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  explicit ListedFile(std::size_t slot) : slot_(slot) {}
  std::size_t slot_ = kNone;
};

// A stretch of work that removeUnfinishedFiles() must not cut: a change to the list, the creation
// of a listed file (so a removal never runs between listing and creating and misses the file), or
// a publication of several files that must not stop half-way (a PNG sequence's commit). While it
// lasts, the calling thread's signals are blocked (they wait, or go to another thread, whose
// removal then waits for the section to end). Sections nest on one thread; keep them short.
class UnfinishedFilesSection {
 public:
  UnfinishedFilesSection();
  ~UnfinishedFilesSection();
  UnfinishedFilesSection(const UnfinishedFilesSection&) = delete;
  UnfinishedFilesSection& operator=(const UnfinishedFilesSection&) = delete;

  // Lists `path`; call it before creating the file, inside the same section.
  ListedFile list(const std::filesystem::path& path) const;
};

// Removes every listed file. For a process about to end: async-signal-safe, it waits for a
// section running on another thread to end, and it leaves the list locked, so no thread creates
// or publishes a file after it. Called on a thread inside a section (a crash there), it removes
// nothing: the list may be half changed. Called again on a thread whose removal it interrupts or
// follows (a handler inside a handler), it removes them again rather than wait for itself.
void removeUnfinishedFiles() noexcept;

// Files listed now (for tests).
std::size_t unfinishedFileCount();

}  // namespace coinroll::io
