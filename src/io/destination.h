#pragma once
// What an output name the user gave turns out to be, found once before any work, so every
// writer treats names the way Unix tools do (docs/outputs.md): a symbolic link is followed to
// its target, a device, FIFO or open descriptor is written to directly, and a regular file is
// replaced atomically only if the user could have written it.

#include <sys/types.h>

#include <filesystem>

namespace coinroll::io {

struct Destination {
  enum class Kind {
    NewFile,      // nothing there yet: created (through a temporary and a rename)
    RegularFile,  // an existing regular file: replaced atomically, keeping its mode
    Device,       // a character or block device, FIFO or socket: opened and written in place
    Descriptor,   // a descriptor of this process (/dev/stdout, /dev/fd/N, /proc/self/fd/N): written to it
  };

  Kind kind = Kind::NewFile;
  std::filesystem::path name;  // as the user gave it: what messages say
  std::filesystem::path path;  // where the bytes go: its directory made canonical, links followed
                               // (empty for a Descriptor)
  int descriptor = -1;         // Kind::Descriptor: the descriptor the name stands for
  mode_t mode = 0;             // Kind::RegularFile: the existing file's permission bits
  uid_t owner = 0;             // Kind::RegularFile: the existing file's owner and group
  gid_t group = 0;

  // True when the content is streamed (no temporary, no rename): Device or Descriptor.
  bool isStream() const { return kind == Kind::Device || kind == Kind::Descriptor; }
};

// Follows `name` through symbolic links (relative targets from the link's directory, at most 40
// hops) and classifies what it reaches. Throws std::invalid_argument for an empty name and
// std::runtime_error "NAME: cannot write: WHY" for a name that cannot be an output: a directory,
// a missing directory on the way, a link loop, a name longer than the file system holds.
Destination resolveDestination(const std::filesystem::path& name);

// Refuses, with std::runtime_error naming the file and the fix, a regular file the user could
// not write (faccessat W_OK for the effective user; root passes, as for any Unix tool) or could
// not replace (another user's file in a sticky directory such as /tmp), and a new name in a
// directory the user cannot write. Nothing for streams: opening them is the check.
void checkReplaceable(const Destination& destination);

// resolveDestination and checkReplaceable together: for a command that writes its output only
// at the end (a still), so a name that cannot work is refused before the work.
Destination checkOutputName(const std::filesystem::path& name);

// True when `a` and `b` are one output however they were spelt: the same path once links are
// followed and the directory made canonical, the same file (device and inode: hard links), or the
// same open file behind two descriptors (-, /dev/stdout, /dev/fd/1).
bool sameOutput(const Destination& a, const Destination& b);

// True when `name` resolves to a stream destination; false for files and for names that do not
// resolve at all (whose writer then reports why).
bool namesStream(const std::filesystem::path& name);

}  // namespace coinroll::io
