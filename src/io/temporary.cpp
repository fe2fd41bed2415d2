#include "io/temporary.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>

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

std::filesystem::path hiddenName(const std::filesystem::path& directory, const std::string& stem,
                                 std::string_view tag) {
  const std::string suffix = uniqueSuffix(tag);
  // The output's own name when it fits, so a user can see what is being written; a fixed stem
  // when it does not, so a legal 255-byte name is not refused for its temporary's length.
  std::string fileName = ".";
  fileName.append(stem.size() + suffix.size() + 1 <= kMaxNameBytes ? stem : "coinroll").append(suffix);
  return directory / fileName;
}

bool namedTemporariesRequested() {
  const char* value = std::getenv("COINROLL_NAMED_TEMPORARIES");
  return value != nullptr && std::string_view(value) == "1";
}

// An unnamed file can be given a name, and be opened by the libraries that write by path, only
// through its /proc/self/fd link: without /proc (a chroot, a container that does not mount it)
// the link is missing, or is another file's.
bool reachesItself(int descriptor, const std::filesystem::path& link) {
  struct stat opened {};
  struct stat reached {};
  return ::fstat(descriptor, &opened) == 0 && ::stat(link.c_str(), &reached) == 0 && opened.st_dev == reached.st_dev &&
         opened.st_ino == reached.st_ino;
}

}  // namespace

TemporaryFile::TemporaryFile(TemporaryFile&& other) noexcept
    : path_(std::exchange(other.path_, {})),
      directory_(std::move(other.directory_)),
      stem_(std::move(other.stem_)),
      descriptor_(std::exchange(other.descriptor_, -1)),
      unnamed_(std::exchange(other.unnamed_, false)),
      listed_(std::move(other.listed_)) {}

TemporaryFile& TemporaryFile::operator=(TemporaryFile&& other) noexcept {
  if (this != &other) {
    remove();
    path_ = std::exchange(other.path_, {});
    directory_ = std::move(other.directory_);
    stem_ = std::move(other.stem_);
    descriptor_ = std::exchange(other.descriptor_, -1);
    unnamed_ = std::exchange(other.unnamed_, false);
    listed_ = std::move(other.listed_);
  }
  return *this;
}

TemporaryFile TemporaryFile::createIn(const std::filesystem::path& directory, const std::string& stem, mode_t mode,
                                      const std::filesystem::path& name, bool unnamedAllowed) {
  TemporaryFile file;
  file.directory_ = directory;
  file.stem_ = stem;
  const auto cannotWrite = [&](int error) {
    return std::runtime_error(name.string() + ": cannot write in '" + directory.string() +
                              "': " + std::strerror(error));
  };
  if (unnamedAllowed && !namedTemporariesRequested()) {
    const int descriptor = ::open(directory.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, mode);
    if (descriptor >= 0) {
      std::filesystem::path link = "/proc/self/fd/" + std::to_string(descriptor);
      if (reachesItself(descriptor, link)) {
        file.path_ = std::move(link);
        file.descriptor_ = descriptor;
        file.unnamed_ = true;
        return file;
      }
      ::close(descriptor);
    } else if (errno != EOPNOTSUPP && errno != EISDIR && errno != EINVAL) {
      // The file system takes O_TMPFILE (it would have said EOPNOTSUPP, or EISDIR and EINVAL for
      // a kernel that does not know it) and refused the file itself: full, read-only, no access.
      throw cannotWrite(errno);
    }
  }
  for (int attempt = 0;; ++attempt) {
    const std::filesystem::path path = hiddenName(directory, stem, "partial");
    const UnfinishedFilesSection section;  // listed before it exists: an ending process removes it
    ListedFile listed = section.list(path);
    const int descriptor = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, mode);
    if (descriptor >= 0) {
      file.path_ = path;
      file.descriptor_ = descriptor;
      file.listed_ = std::move(listed);
      return file;
    }
    const int error = errno;
    if (error != EEXIST || attempt == kMaxAttempts) throw cannotWrite(error);
  }
}

int TemporaryFile::giveName() {
  if (!unnamed_) return 0;
  for (int attempt = 0;; ++attempt) {
    const std::filesystem::path name = hiddenName(directory_, stem_, "partial");
    const UnfinishedFilesSection section;  // listed before it exists, as a named temporary is
    ListedFile listed = section.list(name);
    // AT_SYMLINK_FOLLOW through /proc rather than AT_EMPTY_PATH on the descriptor, which needs
    // CAP_DAC_READ_SEARCH.
    if (::linkat(AT_FDCWD, path_.c_str(), AT_FDCWD, name.c_str(), AT_SYMLINK_FOLLOW) == 0) {
      path_ = name;
      unnamed_ = false;
      listed_ = std::move(listed);
      return 0;
    }
    const int error = errno;
    if (error != EEXIST || attempt == kMaxAttempts) return error;
  }
}

int TemporaryFile::closeDescriptor() {
  if (descriptor_ < 0) return 0;
  const int descriptor = std::exchange(descriptor_, -1);
  if (unnamed_) {
    path_.clear();
    unnamed_ = false;
  }
  return ::close(descriptor) != 0 && errno != EINTR ? errno : 0;
}

int TemporaryFile::moveOnto(const std::filesystem::path& target) {
  if (unnamed_ || path_.empty()) throw std::logic_error(target.string() + ": moveOnto() of a temporary with no name");
  if (std::rename(path_.c_str(), target.c_str()) != 0) return errno;
  path_.clear();
  listed_.reset();
  return 0;
}

void TemporaryFile::remove() noexcept {
  if (descriptor_ >= 0) ::close(std::exchange(descriptor_, -1));
  if (!unnamed_ && !path_.empty()) ::unlink(path_.c_str());
  path_.clear();
  unnamed_ = false;
  listed_.reset();
}

std::filesystem::path siblingName(const std::filesystem::path& file, std::string_view tag) {
  return hiddenName(file.parent_path(), file.filename().string(), tag);
}

std::string describeMoveError(int error, const std::filesystem::path& target) {
  std::error_code ignored;
  if (error != ENOENT || std::filesystem::is_directory(target.parent_path(), ignored)) return std::strerror(error);
  return std::string(std::strerror(error)) + ": its directory " + target.parent_path().string() +
         " was renamed or removed while it was written";
}

TemporaryFile createTemporaryFor(const Destination& destination, bool unnamedAllowed) {
  TemporaryFile file = TemporaryFile::createIn(destination.path.parent_path(), destination.path.filename().string(),
                                               kNewFileMode, destination.name, unnamedAllowed);
  if (destination.kind != Destination::Kind::RegularFile) return file;
  // Owner and group first: changing them may clear mode bits. Root can keep both; another user
  // keeps the group when a member of it, and otherwise the file becomes theirs, as with cp(1).
  const bool root = ::geteuid() == 0;
  if (root || destination.group != ::getegid()) {
    [[maybe_unused]] const int kept =
        ::fchown(file.descriptor(), root ? destination.owner : static_cast<uid_t>(-1), destination.group);
  }
  if (::fchmod(file.descriptor(), destination.mode) != 0) {
    const int error = errno;
    file.remove();
    throw std::runtime_error(destination.name.string() +
                             ": cannot keep its permissions on the new content: " + std::strerror(error));
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
  return TemporaryFile::createIn(directory, "coinroll-output", kPrivateMode, destination.name, true);
}

}  // namespace coinroll::io
