#pragma once
// Hidden files of our own beside an output: the temporary a file is written under before its
// rename, and the copy of a replaced file a PNG sequence keeps until all its frames are in place.
// Internal to src/io.

#include <filesystem>
#include <string_view>

#include "io/destination.h"
#include "io/unfinished_files.h"

namespace coinroll::io {

struct TemporaryFile {
  std::filesystem::path path;
  int descriptor = -1;  // open for writing; the caller closes it
  ListedFile listed;    // on the list of unfinished files until the caller publishes or removes it
};

// ".NAME.TAG-PID-N" beside `file` ("coinroll" for NAME when the whole would not fit in one file
// name): hidden, in the same directory so a rename onto `file` is atomic, and unique among the
// threads and processes writing there. Only a name: nothing is created.
std::filesystem::path siblingName(const std::filesystem::path& file, std::string_view tag);

// Creates (O_EXCL, so it is ours alone, and listed as unfinished before it exists) the temporary for `destination`, a
// NewFile or a RegularFile, beside destination.path. A new file gets 0666 less the umask, as any output; a replacement
// gets the permission bits of the file it replaces (set before any content is written) and, where the system lets us
// (always as root), its owner and group. Throws std::runtime_error naming destination.name.
TemporaryFile createTemporaryFor(const Destination& destination);

// Creates a private (0600) temporary in the system's temporary directory ($TMPDIR, else /tmp),
// for a stream destination whose writer needs a seekable file.
TemporaryFile createScratchFileFor(const Destination& destination);

}  // namespace coinroll::io
