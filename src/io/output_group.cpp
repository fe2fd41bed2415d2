#include "io/output_group.h"

#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "io/output_file.h"
#include "io/temporary.h"
#include "io/unfinished_files.h"

namespace coinroll::io {

namespace {

// The share (1/4) of the limit on open files a group's unnamed temporaries may hold: the rest is left to
// the encoders, the renderer and the caller (a quarter of the usual 1024 is 256 frames).
constexpr rlim_t kUnnamedShareOfOpenFiles = 4;

std::size_t unnamedTemporaryBudget() {
  rlimit limit{};
  if (::getrlimit(RLIMIT_NOFILE, &limit) != 0) return 0;
  if (limit.rlim_cur == RLIM_INFINITY) return static_cast<std::size_t>(-1);
  return static_cast<std::size_t>(limit.rlim_cur / kUnnamedShareOfOpenFiles);
}

}  // namespace

OutputGroup::OutputGroup(std::string what) : what_(std::move(what)) {}

std::filesystem::path OutputGroup::add(const std::filesystem::path& name, const std::string& what) {
  if (committed_) throw std::logic_error(name.string() + ": add() after commit()");
  const std::string& content = what.empty() ? what_ : what;
  Destination destination = resolveDestination(name);
  if (destination.isStream()) {
    throw std::runtime_error(name.string() +
                             ": cannot write: not a regular file (a device, FIFO or open descriptor); each " + content +
                             " of a sequence is a file of its own");
  }
  checkReplaceable(destination);
  refuseSharedTarget(destination, content);
  Staged file;
  file.temporary = createTemporaryFor(destination, unnamedTemporaries_ < unnamedTemporaryBudget());
  if (file.temporary.isUnnamed()) {
    ++unnamedTemporaries_;
  } else {
    file.temporary.closeDescriptor();  // the caller writes it by path, and a sequence has thousands
  }
  file.path = file.temporary.path();
  file.destination = std::move(destination);
  file.what = content;
  staged_.push_back(std::move(file));
  return staged_.back().path;
}

void OutputGroup::protect(const std::vector<std::filesystem::path>& inputs) {
  for (const std::filesystem::path& input : inputs) {
    struct stat info {};
    if (::stat(input.c_str(), &info) == 0) protected_.emplace(FileIdentity{info.st_dev, info.st_ino}, input);
  }
}

std::optional<std::filesystem::path> OutputGroup::inputBehind(const std::filesystem::path& name) const {
  struct stat info {};
  if (::stat(name.c_str(), &info) != 0) return std::nullopt;
  const auto input = protected_.find(FileIdentity{info.st_dev, info.st_ino});
  if (input == protected_.end()) return std::nullopt;
  return input->second;
}

// Two outputs written to one file would lose one of them without a word, and an output written to
// an input would destroy it: names are compared by where they lead, links followed.
void OutputGroup::refuseSharedTarget(const Destination& destination, const std::string& what) {
  const auto refuse = [&](const std::string& target) {
    throw std::runtime_error(destination.name.string() + ": cannot write: it leads to " + target);
  };
  const auto sameFileAs = [&](const StagedName& earlier) {
    refuse("the same file as " + earlier.name.string() + " (through a link, or as another name of that file); " +
           (earlier.what == what ? "each " + what + " of a sequence needs a file of its own"
                                 : "the " + earlier.what + " and the " + what + " each need a file of their own"));
  };
  if (const auto earlier = stagedTargets_.find(destination.path); earlier != stagedTargets_.end())
    sameFileAs(earlier->second);
  stagedTargets_.emplace(destination.path, StagedName{destination.name, what});
  struct stat info {};
  if (::stat(destination.path.c_str(), &info) != 0) return;  // a new file: no other name has it yet
  const FileIdentity identity{info.st_dev, info.st_ino};
  if (const auto input = protected_.find(identity); input != protected_.end()) {
    refuse(input->second.string() +
           ", an input of this command (through a link, or as another name of that file); "
           "choose another output name");
  }
  if (const auto earlier = stagedIdentities_.find(identity); earlier != stagedIdentities_.end())
    sameFileAs(earlier->second);
  stagedIdentities_.emplace(identity, StagedName{destination.name, what});
}

void OutputGroup::retire(const std::filesystem::path& path, const std::string& what) {
  if (committed_) throw std::logic_error(path.string() + ": retire() after commit()");
  Retired file;
  file.path = path;
  file.what = what.empty() ? what_ : what;
  retired_.push_back(std::move(file));
}

void OutputGroup::keepPrevious(Staged& file) {
  const std::filesystem::path& path = file.destination.path;
  struct stat info {};
  if (::lstat(path.c_str(), &info) != 0) {
    if (errno == ENOENT) return;  // a new name: nothing to keep
    throw std::runtime_error(file.destination.name.string() + ": " + std::strerror(errno));
  }
  if (!S_ISREG(info.st_mode)) {
    throw std::runtime_error(file.destination.name.string() + ": is no longer a regular file; the " + file.what +
                             " cannot replace it");
  }
  file.previous = siblingName(path, "previous");
  const UnfinishedFilesSection section;  // within commit()'s: listed before it exists
  file.listedPrevious = section.list(file.previous);
  // A second hard link keeps the name on the earlier file until the rename replaces it; where
  // hard links are refused (some file systems, or another user's file under
  // fs.protected_hardlinks) the file is moved aside, and the name is missing for a moment.
  if (::link(path.c_str(), file.previous.c_str()) == 0) {
    file.previousIsLink = true;
    return;
  }
  if (std::rename(path.c_str(), file.previous.c_str()) == 0) return;
  const int error = errno;
  file.previous.clear();
  file.listedPrevious.reset();
  throw std::runtime_error(file.destination.name.string() +
                           ": cannot set the earlier file aside: " + std::strerror(error));
}

void OutputGroup::commit() {
  if (committed_) throw std::logic_error("commit() called twice");
  {
    // A process ending at once (io/unfinished_files.h) waits for this section, so it never
    // leaves the directory half published: it finds the commit done, or undone.
    const UnfinishedFilesSection section;
    try {
      for (Staged& file : staged_) {
        const auto cannotMove = [&](int error) {
          return std::runtime_error(file.destination.name.string() + ": cannot move the finished " + file.what +
                                    " into place: " + describeMoveError(error, file.destination.path));
        };
        // An unnamed temporary needs a name for rename(2), the one call that replaces a file
        // atomically; it is listed from then on, so an ending process removes it like the others.
        if (const int error = file.temporary.giveName(); error != 0) throw cannotMove(error);
        if (const int error = file.temporary.closeDescriptor(); error != 0) {
          throw std::runtime_error(file.destination.name.string() + ": writing the " + file.what +
                                   " failed: " + describeWriteError(error));
        }
        keepPrevious(file);
        if (const int error = file.temporary.moveOnto(file.destination.path); error != 0) throw cannotMove(error);
        file.placed = true;
      }
      for (Retired& old : retired_) {
        const std::filesystem::path previous = siblingName(old.path, "previous");
        ListedFile listed = section.list(previous);
        if (std::rename(old.path.c_str(), previous.c_str()) == 0) {
          old.previous = previous;
          old.listedPrevious = std::move(listed);
        } else if (errno != ENOENT) {  // already gone is as good as removed
          throw std::runtime_error(old.path.string() + ": cannot remove this " + old.what +
                                   " left from an earlier, longer sequence: " + std::strerror(errno));
        }
      }
    } catch (const std::runtime_error& error) {
      const std::string problems = rollBack();
      throw std::runtime_error(
          std::string(error.what()) +
          (problems.empty() ? "; nothing was published and the earlier files are as they were" : problems));
    }
    committed_ = true;
  }
  for (Staged& file : staged_) {
    if (!file.previous.empty()) ::unlink(file.previous.c_str());
    file.listedPrevious.reset();
  }
  for (Retired& old : retired_) {
    if (!old.previous.empty()) ::unlink(old.previous.c_str());
    old.listedPrevious.reset();
  }
}

std::string OutputGroup::rollBack() {
  std::string problems;
  // Either way the kept file is no longer unfinished: back under its name, or the one copy of the
  // user's earlier content, which the message names and an ending process must not remove.
  const auto restore = [&](std::filesystem::path& previous, ListedFile& listed, const std::filesystem::path& path) {
    if (std::rename(previous.c_str(), path.c_str()) == 0) {
      previous.clear();
    } else {
      problems += "; " + path.string() + " could not be restored (" + std::strerror(errno) +
                  "): its earlier content is in " + previous.string();
    }
    listed.reset();
  };
  for (auto old = retired_.rbegin(); old != retired_.rend(); ++old) {
    if (!old->previous.empty()) restore(old->previous, old->listedPrevious, old->path);
  }
  for (auto file = staged_.rbegin(); file != staged_.rend(); ++file) {
    const std::filesystem::path& path = file->destination.path;
    if (file->placed) {
      // The new file is under the name: the earlier one goes back over it, or it goes.
      if (!file->previous.empty()) {
        restore(file->previous, file->listedPrevious, path);
      } else {
        ::unlink(path.c_str());
      }
      file->placed = false;
    } else if (!file->previous.empty()) {
      if (file->previousIsLink) {
        ::unlink(file->previous.c_str());  // the name never left the earlier file
        file->previous.clear();
        file->listedPrevious.reset();
      } else {
        restore(file->previous, file->listedPrevious, path);
      }
    }
  }
  return problems;
}

}  // namespace coinroll::io
