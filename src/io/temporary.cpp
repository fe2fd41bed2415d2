#include "io/temporary.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <system_error>

namespace coinroll::io {

namespace {

// Bytes in one file name on Linux file systems (NAME_MAX).
constexpr std::size_t kMaxNameBytes = 255;
// Tries before giving up on a free name (each clash means another writer took that one).
constexpr int kMaxAttempts = 100;
// A temporary in the shared temporary directory holds the user's output: theirs alone.
constexpr mode_t kPrivateMode = 0600;
// Every output is created like this, so the umask decides its permissions.
constexpr mode_t kNewFileMode = 0666;

// Process-wide, so two outputs with the same name in one process (threads, or a test) never
// pick the same temporary; the PID separates processes.
std::atomic<unsigned> nameCounter{0};

std::string uniqueSuffix(std::string_view tag) {
  // Built with append: GCC 12 flags `"." + std::string` with a false -Wrestrict (GCC bug 105651).
  std::string suffix = ".";
  suffix.append(tag).append("-").append(std::to_string(::getpid())).append("-").append(std::to_string(nameCounter++));
  return suffix;
}

TemporaryFile createExclusive(const std::filesystem::path& directory, const std::string& stem, std::string_view tag,
                              mode_t mode, const std::filesystem::path& name) {
  for (int attempt = 0;; ++attempt) {
    const std::string suffix = uniqueSuffix(tag);
    // The output's own name when it fits, so a user can see what is being written; a fixed stem
    // when it does not, so a legal 255-byte name is not refused for its temporary's length.
    std::string fileName = ".";
    fileName.append(stem.size() + suffix.size() + 1 <= kMaxNameBytes ? stem : "coinroll").append(suffix);
    const std::filesystem::path path = directory / fileName;
    const UnfinishedFilesSection section;  // listed before it exists: an ending process removes it
    ListedFile listed = section.list(path);
    const int descriptor = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, mode);
    if (descriptor >= 0) return {path, descriptor, std::move(listed)};
    if (errno != EEXIST || attempt == kMaxAttempts) {
      throw std::runtime_error(name.string() + ": cannot write in '" + directory.string() +
                               "': " + std::strerror(errno));
    }
  }
}

}  // namespace

std::filesystem::path siblingName(const std::filesystem::path& file, std::string_view tag) {
  const std::string suffix = uniqueSuffix(tag);
  const std::string stem = file.filename().string();
  std::string fileName = ".";
  fileName.append(stem.size() + suffix.size() + 1 <= kMaxNameBytes ? stem : "coinroll").append(suffix);
  return file.parent_path() / fileName;
}

TemporaryFile createTemporaryFor(const Destination& destination) {
  TemporaryFile file = createExclusive(destination.path.parent_path(), destination.path.filename().string(), "partial",
                                       kNewFileMode, destination.name);
  if (destination.kind != Destination::Kind::RegularFile) return file;
  // Owner and group first: changing them may clear mode bits. Root can keep both; another user
  // keeps the group when a member of it, and otherwise the file becomes theirs, as with cp(1).
  const bool root = ::geteuid() == 0;
  if (root || destination.group != ::getegid()) {
    [[maybe_unused]] const int kept =
        ::fchown(file.descriptor, root ? destination.owner : static_cast<uid_t>(-1), destination.group);
  }
  if (::fchmod(file.descriptor, destination.mode) != 0) {
    const int error = errno;
    ::close(file.descriptor);
    ::unlink(file.path.c_str());
    throw std::runtime_error(destination.name.string() + ": cannot keep its permissions on the new content: " +
                             std::strerror(error));
  }
  return file;
}

TemporaryFile createScratchFileFor(const Destination& destination) {
  // POSIX's rule, which std::filesystem::temp_directory_path does not keep: an empty $TMPDIR is
  // as good as none, and none means /tmp.
  const char* variable = std::getenv("TMPDIR");
  const std::filesystem::path directory = variable != nullptr && *variable != '\0' ? variable : "/tmp";
  std::error_code error;
  if (!std::filesystem::is_directory(directory, error)) {
    throw std::runtime_error(destination.name.string() +
                             ": no temporary directory to encode in: " + directory.string() +
                             (error ? ": " + error.message() : std::string(" is not a directory")) +
                             (variable != nullptr && *variable != '\0' ? " (from $TMPDIR)" : ""));
  }
  return createExclusive(directory, "coinroll-output", "partial", kPrivateMode, destination.name);
}

}  // namespace coinroll::io
