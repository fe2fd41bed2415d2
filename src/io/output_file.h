#pragma once
// The one output layer every command writes through (docs/outputs.md). What happens depends on
// what the name turns out to be (io/destination.h):
// - a new name or a regular file: the content goes to a temporary beside it (unnamed where the
//   file system allows, so not even SIGKILL leaves it; io/temporary.h) and is renamed onto it by
//   commit(), so a failed or interrupted run never leaves a truncated file under the name
//   (rename(2) within one directory is atomic); a replaced file keeps its
//   permission bits (and, as root, its owner); a file the user could not write is refused;
// - a symbolic link: the same for the file it leads to; the link stays a link;
// - a device, FIFO or descriptor (/dev/null, a FIFO, /dev/stdout, /dev/fd/N from `>(...)`):
//   written in place as the content is made; what was written before a failure stays written
//   (a pipe cannot take bytes back), as with `--csv -`.
// Every write and the close are checked: a full disk, a file-size limit or a vanished reader is
// an exception naming the output and the system's reason.

#include <filesystem>
#include <memory>
#include <ostream>
#include <string>
#include <string_view>

#include "io/destination.h"
#include "io/output_group.h"
#include "io/temporary.h"

namespace coinroll::io {

// The system's text for a failed write's `error` (strerror), naming for EFBIG the limit that was
// reached: "File too large (the file-size limit, ulimit -f, is 512 bytes)".
std::string describeWriteError(int error);

class OutputFile {
 public:
  enum class Access {
    Sequential,  // the content is written front to back through write() or stream()
    ByPath,      // a library writes temporaryPath() itself and may seek and reread it (the MP4
                 // muxer moving its index to the front); for a stream destination the file is
                 // made in $TMPDIR and copied to the stream by commit()
  };

  // Resolves and checks `name` and opens what the content goes to, so a name that cannot work
  // fails here, before any work. `what` names the content in messages ("CSV" gives
  // "o.csv: writing the CSV failed: No space left on device"). Throws std::invalid_argument for
  // an empty name, std::runtime_error naming it otherwise.
  // With a `group`, a file (not a stream) is one of the group's: staged there, so it is compared
  // with the group's other files by where it leads, and published by the group's commit() with
  // them, all or none; the group, which must outlive this, removes the temporary if it never is.
  OutputFile(const std::filesystem::path& name, std::string what, Access access = Access::Sequential,
             OutputGroup* group = nullptr);
  ~OutputFile();  // without commit(): removes the temporary; a stream is closed as it is

  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  const Destination& destination() const { return destination_; }
  const std::filesystem::path& name() const { return destination_.name; }

  // Access::ByPath: the file to write, by this name only while this object lives (an unnamed
  // temporary's is /proc/self/fd/N). Empty for a Sequential stream, which has none.
  const std::filesystem::path& temporaryPath() const { return temporary_; }

  // Access::Sequential: appends bytes (std::runtime_error naming the output on a failed write).
  void write(std::string_view bytes);
  // Access::Sequential: a buffered stream over write(); a failed write throws from the insertion
  // that reached it (its exception mask holds badbit), so a long run stops at the first failure.
  std::ostream& stream();

  // Completes the output: flushes and closes, then renames the temporary into place (for a file
  // of a group, the group's commit() does), or copies it to the stream (Access::ByPath). Throws
  // std::runtime_error naming the output.
  void commit();

 private:
  class StreamBuffer;
  void requireSequential() const;
  void writeBytes(const char* data, std::size_t size);
  [[noreturn]] void failWrite(int error) const;
  void copyTemporaryToStream();

  Destination destination_;
  std::string what_;
  const Access access_;
  std::filesystem::path temporary_;  // the file by path: beside the destination, or in $TMPDIR
  TemporaryFile ownTemporary_;       // temporary_ when it is not a group's
  bool grouped_ = false;             // temporary_ is an OutputGroup's, published and removed by it
  int descriptor_ = -1;              // where Sequential bytes go: the temporary (a descriptor of
                                     // our own), or the stream
  std::unique_ptr<StreamBuffer> buffer_;
  std::unique_ptr<std::ostream> stream_;
  bool committed_ = false;
};

}  // namespace coinroll::io
