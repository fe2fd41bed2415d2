#pragma once
// Files published together or not at all: a run's outputs, such as a PNG sequence's frames, or a
// video and its sidecar (docs/outputs.md). Each file is written under a temporary beside its name
// (unnamed, or hidden: io/temporary.h); commit() renames them all into place and
// removes the files retired with them, and if any step fails it undoes the steps before it, so
// the directory holds the earlier files exactly as they were. No file system renames many files
// in one step, so a reader looking while commit() runs (a few milliseconds for thousands of
// files) may see some new files beside old ones; a failure or an interruption never leaves that.

#include <sys/types.h>

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "io/destination.h"
#include "io/temporary.h"
#include "io/unfinished_files.h"

namespace coinroll::io {

class OutputGroup {
 public:
  // `what` names one file's content in messages ("PNG"), for the files add() and retire() are not
  // told another name for.
  explicit OutputGroup(std::string what = "output");
  ~OutputGroup() = default;  // without commit(): removes the temporaries; the earlier files stay

  OutputGroup(const OutputGroup&) = delete;
  OutputGroup& operator=(const OutputGroup&) = delete;

  // Stages `name`: resolves it (links followed; it must be a new name or a regular file, since
  // it is published by a rename), refuses it as OutputFile would, creates its temporary with the
  // mode of the file it replaces, and returns the temporary's path for the caller to write (by
  // that name only while the group lives: an unnamed temporary's is /proc/self/fd/N). Each unnamed
  // temporary holds a descriptor until commit(), so past a share of the process's limit on open
  // files (RLIMIT_NOFILE) the rest are named ones. `what` names its content in messages (empty:
  // the group's). Throws std::runtime_error naming `name`.
  std::filesystem::path add(const std::filesystem::path& name, const std::string& what = "");

  // Files add() must never lead to (the command's inputs): a frame name that reaches one, through
  // a link or as another name of the same file, is refused. Files that do not exist are ignored.
  void protect(const std::vector<std::filesystem::path>& inputs);
  // The protected input `name` leads to now, if any: for a caller that can check names before any
  // work is done.
  std::optional<std::filesystem::path> inputBehind(const std::filesystem::path& name) const;

  // An existing file for commit() to remove along with publishing the staged ones (kept if the
  // commit fails). Links are not followed: the name itself goes.
  void retire(const std::filesystem::path& path, const std::string& what = "");

  // Publishes every staged file and removes every retired one, or none of it: throws
  // std::runtime_error naming the file that failed, after putting the earlier files back.
  void commit();

 private:
  struct Staged {
    Destination destination;
    std::string what;
    TemporaryFile temporary;
    std::filesystem::path path;      // the temporary's, as add() returned it
    std::filesystem::path previous;  // the replaced file, kept until the commit holds
    bool previousIsLink = false;     // `previous` is a second hard link: the name kept its file
    bool placed = false;             // the temporary was renamed onto the destination
    ListedFile listedPrevious;       // unfinished files (io/unfinished_files.h) until the commit holds
  };
  struct Retired {
    std::filesystem::path path;
    std::string what;
    std::filesystem::path previous;  // where it was moved; empty while it is still in place
    ListedFile listedPrevious;
  };

  // A file as the system knows it (device and inode): a link, a hard link and the name itself
  // all give the same identity.
  struct FileIdentity {
    dev_t device = 0;
    ino_t inode = 0;
    bool operator<(const FileIdentity& other) const {
      return device != other.device ? device < other.device : inode < other.inode;
    }
  };

  void keepPrevious(Staged& file);
  void refuseSharedTarget(const Destination& destination, const std::string& what);
  std::string rollBack();

  std::string what_;
  std::vector<Staged> staged_;
  std::size_t unnamedTemporaries_ = 0;  // staged temporaries that hold a descriptor
  std::vector<Retired> retired_;
  std::map<FileIdentity, std::filesystem::path> protected_;  // an input's identity -> its name
  // A staged name as messages give it: the name, and what its content is.
  struct StagedName {
    std::filesystem::path name;
    std::string what;
  };
  // Where the staged names lead -> the name that leads there first.
  std::map<std::filesystem::path, StagedName> stagedTargets_;
  std::map<FileIdentity, StagedName> stagedIdentities_;
  bool committed_ = false;
};

}  // namespace coinroll::io
