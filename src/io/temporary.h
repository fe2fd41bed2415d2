#pragma once
// Hidden files of our own beside an output: the temporary a file is written under before its
// rename, and the copy of a replaced file a PNG sequence keeps until all its frames are in place.
// Internal to src/io: other folders write through OutputFile and OutputGroup.

#include <sys/types.h>

#include <filesystem>
#include <string>
#include <string_view>

#include "io/destination.h"
#include "io/unfinished_files.h"

namespace coinroll::io {

// The file an output is written under until it is complete. Where the directory's file system
// allows it (O_TMPFILE: ext4, xfs, btrfs, tmpfs, ...) the file has no name while it is written, so
// the kernel frees it however the process ends, SIGKILL included (docs/outputs.md "Temporaries have
// no name while they are written"); it gets a name only when published. Elsewhere (NFS, CIFS, a
// system without /proc) it is a hidden name beside the output, on the list of unfinished files
// until it is published or removed, as before.
// Move-only; destroyed unpublished, it is closed and its name, if it has one, removed.
class TemporaryFile {
 public:
  TemporaryFile() = default;
  ~TemporaryFile() { remove(); }
  TemporaryFile(TemporaryFile&& other) noexcept;
  TemporaryFile& operator=(TemporaryFile&& other) noexcept;
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;

  // The name to open it by: its hidden name, or for an unnamed one "/proc/self/fd/N", which opens
  // this very file (even after its directory is renamed) for as long as descriptor() is open.
  const std::filesystem::path& path() const { return path_; }
  // Open for writing until closeDescriptor(); an unnamed temporary lives only while it is open.
  int descriptor() const { return descriptor_; }
  bool isUnnamed() const { return unnamed_; }

  // Gives an unnamed temporary a fresh hidden name in its directory (linkat, which never replaces
  // a file), on the list of unfinished files from before it exists; nothing for a named one.
  // Returns 0, or the errno of the failure.
  int giveName();
  // Closes the descriptor (a named temporary needs none to live); returns 0, or the errno of a
  // failed close, which some file systems (NFS) use to report a failed write.
  int closeDescriptor();
  // Renames the named temporary onto `target`, after which it is no longer ours to remove.
  // Returns 0, or the errno of the failure.
  int moveOnto(const std::filesystem::path& target);
  // Closes it and removes its name; an unnamed one is gone once closed. For a temporary that
  // will not be published (or was read back and copied elsewhere).
  void remove() noexcept;

 private:
  friend TemporaryFile createTemporaryFor(const Destination& destination, bool unnamedAllowed);
  friend TemporaryFile createScratchFileFor(const Destination& destination);
  // In `directory`, for the output `stem` (named `name` in messages), with permission bits `mode`.
  static TemporaryFile createIn(const std::filesystem::path& directory, const std::string& stem, mode_t mode,
                                const std::filesystem::path& name, bool unnamedAllowed);
  std::filesystem::path path_;       // empty once published or removed
  std::filesystem::path directory_;  // where it is, and where an unnamed one is given its name
  std::string stem_;                 // the output's file name, for the hidden name
  int descriptor_ = -1;
  bool unnamed_ = false;
  ListedFile listed_;  // a named one: on the list of unfinished files until published or removed
};

// ".NAME.TAG-PID-N" beside `file` ("coinroll" for NAME when the whole would not fit in one file
// name): hidden, in the same directory so a rename onto `file` is atomic, and unique among the
// threads and processes writing there. Only a name: nothing is created.
std::filesystem::path siblingName(const std::filesystem::path& file, std::string_view tag);

// The reason a temporary could not be named or moved onto `target` (error: the errno), saying so
// when `target`'s directory is gone: renamed or removed while the output was written.
std::string describeMoveError(int error, const std::filesystem::path& target);

// Creates the temporary for `destination`, a NewFile or a RegularFile, in destination.path's
// directory: unnamed where the file system allows it and `unnamedAllowed`, else named (O_EXCL, so
// it is ours alone, and listed as unfinished before it exists). A new file gets 0666 less the
// umask, as any output; a replacement gets the permission bits of the file it replaces (set
// before any content is written) and, where the system lets us (always as root), its owner and
// group. Throws std::runtime_error naming destination.name.
// The environment variable COINROLL_NAMED_TEMPORARIES=1 makes every temporary named: for the
// tests of that path, and as a way out on a file system that takes O_TMPFILE but mishandles it.
TemporaryFile createTemporaryFor(const Destination& destination, bool unnamedAllowed = true);

// Creates a private (0600) temporary in the system's temporary directory ($TMPDIR, else /tmp),
// for a stream destination whose writer needs a seekable file; unnamed where it can be.
TemporaryFile createScratchFileFor(const Destination& destination);

}  // namespace coinroll::io
