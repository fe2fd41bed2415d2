#include "io/destination.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>
#include <system_error>

namespace coinroll::io {

namespace {

// Links followed before giving up with ELOOP: Linux's own limit (MAXSYMLINKS).
constexpr int kMaxLinkHops = 40;
// Bytes in one file name when pathconf cannot say (NAME_MAX of Linux file systems).
constexpr std::size_t kMaxNameBytes = 255;
// Digits of the largest descriptor number we read (an int).
constexpr std::size_t kMaxDescriptorDigits = 9;

std::runtime_error cannotWrite(const std::filesystem::path& name, const std::string& why) {
  return std::runtime_error(name.string() + ": cannot write: " + why);
}

std::optional<int> descriptorNumber(const std::string& text) {
  if (text.empty() || text.size() > kMaxDescriptorDigits) return std::nullopt;
  for (const char c : text) {
    if (c < '0' || c > '9') return std::nullopt;
  }
  return std::stoi(text);
}

// The names bash itself treats as descriptors, so they work even where /proc is not mounted.
std::optional<int> descriptorNamedLexically(const std::filesystem::path& path) {
  const std::filesystem::path normal = path.lexically_normal();
  if (normal == "/dev/stdin") return 0;
  if (normal == "/dev/stdout") return 1;
  if (normal == "/dev/stderr") return 2;
  if (normal.parent_path() == "/dev/fd") return descriptorNumber(normal.filename().string());
  return std::nullopt;
}

// /proc/self/fd and /dev/fd made canonical: "/proc/PID/fd" or "/proc/PID/task/TID/fd" for our PID.
// Their entries are links to whatever the descriptor holds ("pipe:[1234]" for a pipe), which must
// not be followed: the descriptor is the destination.
bool isOwnDescriptorDirectory(const std::filesystem::path& directory) {
  const std::string text = directory.string();
  const std::string own = "/proc/" + std::to_string(::getpid());
  if (text == own + "/fd") return true;
  const std::string task = own + "/task/";
  if (text.size() <= task.size() + 3 || text.compare(0, task.size(), task) != 0 ||
      text.compare(text.size() - 3, 3, "/fd") != 0) {
    return false;
  }
  return descriptorNumber(text.substr(task.size(), text.size() - 3 - task.size())).has_value();
}

// " (through the link, 'TARGET')" when links were followed, so a message about the target does
// not seem to be about the name the user typed.
std::string viaLinks(const std::filesystem::path& name, const std::filesystem::path& current) {
  return current == name ? std::string() : " (where the link leads, '" + current.string() + "')";
}

}  // namespace

Destination resolveDestination(const std::filesystem::path& name) {
  if (name.empty()) throw std::invalid_argument("the output name is empty; give a file name");
  Destination destination;
  destination.name = name;
  std::filesystem::path current = name;
  for (int hops = 0;; ++hops) {
    if (const std::optional<int> descriptor = descriptorNamedLexically(current)) {
      destination.kind = Destination::Kind::Descriptor;
      destination.descriptor = *descriptor;
      return destination;
    }
    const std::filesystem::path fileName = current.filename();
    if (fileName.empty() || fileName == "." || fileName == "..") {
      throw cannotWrite(name, "'" + current.string() + "' names a directory; give a file name");
    }
    const std::filesystem::path written = current.parent_path().empty() ? "." : current.parent_path();
    std::error_code error;
    const std::filesystem::path directory = std::filesystem::canonical(written, error);
    if (error == std::errc::no_such_file_or_directory) {
      throw cannotWrite(name, "directory '" + written.string() + "' does not exist" + viaLinks(name, current));
    }
    if (error == std::errc::not_a_directory || (!error && !std::filesystem::is_directory(directory, error))) {
      throw cannotWrite(name, "'" + written.string() + "' is not a directory" + viaLinks(name, current));
    }
    if (error) throw cannotWrite(name, "directory '" + written.string() + "': " + error.message());

    if (isOwnDescriptorDirectory(directory)) {
      if (const std::optional<int> descriptor = descriptorNumber(fileName.string())) {
        destination.kind = Destination::Kind::Descriptor;
        destination.descriptor = *descriptor;
        return destination;
      }
    }
    // Checked before lstat, which would say only ENAMETOOLONG; and for a new name this is the
    // failure that would otherwise come at the final rename, after all the work.
    const long nameLimit = ::pathconf(directory.c_str(), _PC_NAME_MAX);
    const std::size_t maxNameBytes = nameLimit > 0 ? static_cast<std::size_t>(nameLimit) : kMaxNameBytes;
    if (const std::size_t nameBytes = fileName.string().size(); nameBytes > maxNameBytes) {
      throw cannotWrite(name, std::string(std::strerror(ENAMETOOLONG)) + " (" + std::to_string(nameBytes) +
                                  " bytes; this file system allows " + std::to_string(maxNameBytes) + ")" +
                                  viaLinks(name, current));
    }
    const std::filesystem::path path = directory / fileName;
    struct stat info {};
    if (::lstat(path.c_str(), &info) != 0) {
      if (errno != ENOENT) throw cannotWrite(name, std::strerror(errno) + viaLinks(name, current));
      destination.kind = Destination::Kind::NewFile;  // a dangling link creates its target, as `>` does
      destination.path = path;
      return destination;
    }
    if (S_ISLNK(info.st_mode)) {
      if (hops == kMaxLinkHops) throw cannotWrite(name, std::strerror(ELOOP));
      const std::filesystem::path target = std::filesystem::read_symlink(path, error);
      if (error) throw cannotWrite(name, "reading the link '" + path.string() + "': " + error.message());
      current = target.is_absolute() ? target : directory / target;
      continue;
    }
    if (S_ISDIR(info.st_mode)) throw cannotWrite(name, "is a directory; give a file name" + viaLinks(name, current));
    destination.path = path;
    if (!S_ISREG(info.st_mode)) {
      destination.kind = Destination::Kind::Device;
      return destination;
    }
    destination.kind = Destination::Kind::RegularFile;
    // Permission bits only: set-user-ID, set-group-ID and sticky bits are not carried to new
    // content (as cp(1) does when it cannot keep the owner).
    destination.mode = info.st_mode & 0777;
    destination.owner = info.st_uid;
    destination.group = info.st_gid;
    return destination;
  }
}

void checkReplaceable(const Destination& destination) {
  if (destination.isStream()) return;
  const std::filesystem::path directory = destination.path.parent_path();
  const std::string& name = destination.name.string();
  if (destination.kind == Destination::Kind::RegularFile) {
    // The rename would succeed in a writable directory whatever the file's own mode: refuse what
    // `>` would refuse. AT_EACCESS: the effective user, the one that would do the writing.
    if (::faccessat(AT_FDCWD, destination.path.c_str(), W_OK, AT_EACCESS) != 0) {
      throw std::runtime_error(
          name + ": cannot write: " + std::strerror(errno) +
          ": the file is not writable for you; make it writable (chmod u+w) or choose another name");
    }
    // In a sticky directory (/tmp) only the file's or the directory's owner may rename onto it; the
    // rename would fail only at the end.
    struct stat directoryInfo {};
    const uid_t user = ::geteuid();
    if (::stat(directory.c_str(), &directoryInfo) == 0 && (directoryInfo.st_mode & S_ISVTX) != 0 && user != 0 &&
        destination.owner != user && directoryInfo.st_uid != user) {
      throw std::runtime_error(name + ": cannot write: it belongs to another user in the sticky directory '" +
                               directory.string() + "', where only its owner may replace it; choose another name");
    }
  }
  if (::faccessat(AT_FDCWD, directory.c_str(), W_OK | X_OK, AT_EACCESS) != 0) {
    throw std::runtime_error(name + ": cannot write in '" + directory.string() + "': " + std::strerror(errno));
  }
}

Destination checkOutputName(const std::filesystem::path& name) {
  Destination destination = resolveDestination(name);
  checkReplaceable(destination);
  return destination;
}

bool sameOutput(const Destination& a, const Destination& b) {
  if (!a.path.empty() && a.path == b.path) return true;
  const auto identify = [](const Destination& destination, struct stat& info) {
    if (destination.kind == Destination::Kind::Descriptor) return ::fstat(destination.descriptor, &info) == 0;
    return destination.kind != Destination::Kind::NewFile && ::stat(destination.path.c_str(), &info) == 0;
  };
  struct stat first {
  }, second{};
  return identify(a, first) && identify(b, second) && first.st_dev == second.st_dev && first.st_ino == second.st_ino;
}

bool namesStream(const std::filesystem::path& name) {
  try {
    return resolveDestination(name).isStream();
  } catch (const std::exception&) {
    return false;
  }
}

}  // namespace coinroll::io
