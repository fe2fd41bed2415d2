#include "io/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <system_error>

namespace coinroll::io {

namespace {

// Bytes in one file name on Linux file systems (NAME_MAX).
constexpr std::size_t kMaxNameBytes = 255;

std::filesystem::path directoryOf(const std::filesystem::path& file) {
  const std::filesystem::path parent = file.parent_path();
  return parent.empty() ? std::filesystem::path(".") : parent;
}

}  // namespace

AtomicOutputFile::AtomicOutputFile(std::filesystem::path destination)
    : destination_(std::move(destination)) {
  const std::filesystem::path directory = directoryOf(destination_);
  std::error_code ec;
  if (!std::filesystem::is_directory(directory, ec)) {
    throw std::runtime_error(destination_.string() + ": cannot write: directory '" + directory.string() +
                             "' does not exist");
  }
  // A name longer than the file system holds would fail only at the final rename, after the work.
  const long nameLimit = ::pathconf(directory.c_str(), _PC_NAME_MAX);
  const std::size_t maxNameBytes = nameLimit > 0 ? static_cast<std::size_t>(nameLimit) : kMaxNameBytes;
  if (const std::size_t nameBytes = destination_.filename().string().size(); nameBytes > maxNameBytes) {
    throw std::runtime_error(destination_.string() + ": cannot write: " + std::strerror(ENAMETOOLONG) + " (" +
                             std::to_string(nameBytes) + " bytes; this file system allows " +
                             std::to_string(maxNameBytes) + ")");
  }
  // Renaming onto /dev/null or a FIFO would replace the special file itself.
  if (std::filesystem::exists(destination_, ec) && !std::filesystem::is_regular_file(destination_, ec)) {
    throw std::runtime_error(destination_.string() + ": cannot write: exists and is not a regular file");
  }
  // Creating the file now (O_EXCL, so the name is ours alone) proves the directory is writable
  // before any work starts; mode 0666 lets the umask decide permissions as for any output.
  static std::atomic<unsigned> counter{0};
  for (int attempt = 0;; ++attempt) {
    // Built with append: GCC 12 flags `"." + std::string` with a false -Wrestrict (GCC bug 105651).
    // The destination's own name when it fits, so a user can see what is being written; a fixed
    // stem when it does not, so a legal 255-byte name is not refused for its temporary's length.
    std::string suffix = ".partial-";
    suffix.append(std::to_string(::getpid())).append("-").append(std::to_string(counter++));
    std::string name = ".";
    const std::string stem = destination_.filename().string();
    name.append(stem.size() + suffix.size() + 1 <= kMaxNameBytes ? stem : "coinroll").append(suffix);
    temporary_ = directory / name;
    const int fd = ::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0) {
      ::close(fd);
      break;
    }
    if (errno != EEXIST || attempt > 100) {
      throw std::runtime_error(destination_.string() + ": cannot write in '" + directory.string() +
                               "': " + std::strerror(errno));
    }
  }
}

AtomicOutputFile::~AtomicOutputFile() {
  if (!committed_) {
    std::error_code ignored;
    std::filesystem::remove(temporary_, ignored);
  }
}

void AtomicOutputFile::commit() {
  std::error_code ec;
  std::filesystem::rename(temporary_, destination_, ec);
  if (ec) {
    throw std::runtime_error(destination_.string() + ": cannot move the finished output into place: " +
                             ec.message());
  }
  committed_ = true;
}

}  // namespace coinroll::io
