#include "io/output_file.h"

#include <fcntl.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <streambuf>
#include <system_error>
#include <vector>

#include "io/temporary.h"

namespace coinroll::io {

namespace {

// Bytes stream() gathers before one write(2): few system calls for a CSV of short rows.
constexpr std::size_t kStreamBufferBytes = 64 * 1024;
// Bytes per read when copying an encoded temporary to a stream.
constexpr std::size_t kCopyBufferBytes = 1024 * 1024;

std::string describe(int error) { return std::strerror(error); }

}  // namespace

std::string describeWriteError(int error) {
  rlimit limit{};
  if (error != EFBIG || ::getrlimit(RLIMIT_FSIZE, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY)
    return describe(error);
  return describe(error) + " (the file-size limit, ulimit -f, is " + std::to_string(limit.rlim_cur) + " bytes)";
}

namespace {

// The descriptor a name stands for, duplicated so closing ours leaves the caller's open.
int duplicateForWriting(const Destination& destination) {
  const std::string name = destination.name.string();
  const int flags = ::fcntl(destination.descriptor, F_GETFL);
  if (flags < 0) {
    throw std::runtime_error(name + ": cannot write: descriptor " + std::to_string(destination.descriptor) +
                             " is not open");
  }
  if ((flags & O_ACCMODE) == O_RDONLY) {
    throw std::runtime_error(name + ": cannot write: descriptor " + std::to_string(destination.descriptor) +
                             " is open for reading only");
  }
  const int copy = ::fcntl(destination.descriptor, F_DUPFD_CLOEXEC, 0);
  if (copy < 0) throw std::runtime_error(name + ": cannot write: " + describe(errno));
  return copy;
}

// A device or FIFO is opened as it is: no O_CREAT, no O_TRUNC (neither means anything there).
// Opening a FIFO waits for its reader, as `>` does.
int openDevice(const Destination& destination) {
  int descriptor = -1;
  do {
    descriptor = ::open(destination.path.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
  } while (descriptor < 0 && errno == EINTR);
  if (descriptor < 0) throw std::runtime_error(destination.name.string() + ": cannot write: " + describe(errno));
  return descriptor;
}

// A named temporary lives without a descriptor, and a library that writes by path opens its own;
// an unnamed one lives only while its descriptor is open.
void keepOnlyWhatLivesOn(TemporaryFile& temporary) {
  if (!temporary.isUnnamed()) temporary.closeDescriptor();
}

}  // namespace

// Gathers small insertions into one write(); errors surface as the exception writeBytes throws.
class OutputFile::StreamBuffer : public std::streambuf {
 public:
  explicit StreamBuffer(OutputFile& file) : file_(file), bytes_(kStreamBufferBytes) {
    setp(bytes_.data(), bytes_.data() + bytes_.size());
  }

 protected:
  int_type overflow(int_type c) override {
    drain();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }

  std::streamsize xsputn(const char* data, std::streamsize count) override {
    if (count > epptr() - pptr()) {
      drain();
      if (static_cast<std::size_t>(count) >= bytes_.size()) {
        file_.writeBytes(data, static_cast<std::size_t>(count));
        return count;
      }
    }
    std::memcpy(pptr(), data, static_cast<std::size_t>(count));
    pbump(static_cast<int>(count));
    return count;
  }

  int sync() override {
    drain();
    return 0;
  }

 private:
  void drain() {
    const std::size_t pending = static_cast<std::size_t>(pptr() - pbase());
    setp(bytes_.data(), bytes_.data() + bytes_.size());  // emptied even when the write throws
    if (pending > 0) file_.writeBytes(bytes_.data(), pending);
  }

  OutputFile& file_;
  std::vector<char> bytes_;
};

OutputFile::OutputFile(const std::filesystem::path& name, std::string what, Access access, OutputGroup* group)
    : destination_(resolveDestination(name)), what_(std::move(what)), access_(access) {
  if (destination_.kind == Destination::Kind::Descriptor) {
    descriptor_ = duplicateForWriting(destination_);
  } else if (destination_.kind == Destination::Kind::Device) {
    descriptor_ = openDevice(destination_);
  } else if (group != nullptr) {
    temporary_ = group->add(name, what_);
    grouped_ = true;
    if (access_ == Access::Sequential) {
      descriptor_ = ::open(temporary_.c_str(), O_WRONLY | O_CLOEXEC);
      if (descriptor_ < 0) throw std::runtime_error(destination_.name.string() + ": cannot write: " + describe(errno));
    }
    return;
  } else {
    checkReplaceable(destination_);
    ownTemporary_ = createTemporaryFor(destination_);
    temporary_ = ownTemporary_.path();
    if (access_ == Access::Sequential) {
      // A descriptor of our own, so that its close in commit() is checked before the output is
      // published (NFS reports a failed write only there).
      descriptor_ = ::fcntl(ownTemporary_.descriptor(), F_DUPFD_CLOEXEC, 0);
      if (descriptor_ < 0) throw std::runtime_error(destination_.name.string() + ": cannot write: " + describe(errno));
    }
    keepOnlyWhatLivesOn(ownTemporary_);
    return;
  }
  if (access_ == Access::ByPath) {
    try {
      ownTemporary_ = createScratchFileFor(destination_);
      temporary_ = ownTemporary_.path();
      keepOnlyWhatLivesOn(ownTemporary_);
    } catch (...) {
      ::close(descriptor_);
      throw;
    }
  }
}

OutputFile::~OutputFile() {
  if (descriptor_ >= 0) ::close(descriptor_);
}

std::ostream& OutputFile::stream() {
  requireSequential();
  if (!stream_) {
    buffer_ = std::make_unique<StreamBuffer>(*this);
    stream_ = std::make_unique<std::ostream>(buffer_.get());
    stream_->exceptions(std::ios::badbit);
  }
  return *stream_;
}

void OutputFile::write(std::string_view bytes) {
  requireSequential();
  if (stream_) stream_->flush();  // keeps the order of what went through stream()
  writeBytes(bytes.data(), bytes.size());
}

void OutputFile::failWrite(int error) const {
  throw std::runtime_error(destination_.name.string() + ": writing the " + what_ +
                           " failed: " + describeWriteError(error));
}

void OutputFile::requireSequential() const {
  if (access_ != Access::Sequential || committed_) {
    throw std::logic_error(destination_.name.string() +
                           ": write() or stream() on an output written by path or committed");
  }
}

void OutputFile::writeBytes(const char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t written = ::write(descriptor_, data, size);
    if (written < 0) {
      if (errno == EINTR) continue;
      failWrite(errno);
    }
    data += written;
    size -= static_cast<std::size_t>(written);
  }
}

void OutputFile::copyTemporaryToStream() {
  const int source = ::open(temporary_.c_str(), O_RDONLY | O_CLOEXEC);
  if (source < 0) failWrite(errno);
  // Gone from the directory before the first byte goes out: if the reader vanishes and SIGPIPE
  // ends us during the copy, nothing is left in $TMPDIR (`source` keeps an unnamed one alive).
  ownTemporary_.remove();
  temporary_.clear();
  std::vector<char> bytes(kCopyBufferBytes);
  for (;;) {
    const ssize_t count = ::read(source, bytes.data(), bytes.size());
    if (count == 0) break;
    if (count < 0) {
      if (errno == EINTR) continue;
      const int error = errno;
      ::close(source);
      throw std::runtime_error(destination_.name.string() + ": reading back the encoded " + what_ +
                               " failed: " + describe(error));
    }
    try {
      writeBytes(bytes.data(), static_cast<std::size_t>(count));
    } catch (...) {
      ::close(source);
      throw;
    }
  }
  ::close(source);
}

void OutputFile::commit() {
  if (committed_) throw std::logic_error(destination_.name.string() + ": commit() called twice");
  if (stream_) {
    // A failed insertion threw to the writer; one that caught it must not publish the output.
    if (!*stream_) throw std::runtime_error(destination_.name.string() + ": writing the " + what_ + " failed");
    stream_->flush();
  }
  if (access_ == Access::ByPath && destination_.isStream()) copyTemporaryToStream();
  if (descriptor_ >= 0) {
    const int descriptor = descriptor_;
    descriptor_ = -1;
    // Some file systems (NFS) report a failed write only at close.
    if (::close(descriptor) != 0 && errno != EINTR) failWrite(errno);
  }
  if (!destination_.isStream() && !grouped_) {
    const auto cannotMove = [&](int error) {
      return std::runtime_error(destination_.name.string() + ": cannot move the finished output into place: " +
                                describeMoveError(error, destination_.path));
    };
    // An unnamed temporary is given a hidden name first: rename(2) is what replaces the earlier
    // file atomically, and linkat(2) onto the destination itself would refuse an existing one.
    if (const int error = ownTemporary_.giveName(); error != 0) throw cannotMove(error);
    if (const int error = ownTemporary_.closeDescriptor(); error != 0) failWrite(error);
    if (const int error = ownTemporary_.moveOnto(destination_.path); error != 0) throw cannotMove(error);
  }
  committed_ = true;
}

}  // namespace coinroll::io
