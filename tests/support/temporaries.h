#pragma once
// The output layer's temporaries as a test sees them from outside (io/temporary.h): an unnamed
// one exists only as a descriptor of the process writing it, a named one as a hidden file.

#include <stdlib.h>
#include <sys/types.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>

namespace coinroll::testing {

// The temporaries process `pid` is writing in `directory`: its hidden files there, and the unnamed
// files (O_TMPFILE) it holds open there, whose /proc link reads "DIRECTORY/#INODE (deleted)".
inline int temporariesBeingWritten(pid_t pid, const std::filesystem::path& directory) {
  std::error_code error;
  const std::string unnamedPrefix = std::filesystem::canonical(directory, error).string() + "/#";
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(directory, error))
    count += entry.path().filename().string()[0] == '.';
  const std::filesystem::path descriptors = "/proc/" + std::to_string(pid) + "/fd";
  for (const auto& entry : std::filesystem::directory_iterator(descriptors, error)) {
    const std::string target = std::filesystem::read_symlink(entry.path(), error).string();
    count += !error && target.rfind(unnamedPrefix, 0) == 0;
  }
  return count;
}

// Today's named temporaries for as long as it lives (COINROLL_NAMED_TEMPORARIES=1), in this
// process and the processes it starts: the path a file system without O_TMPFILE takes.
class NamedTemporaries {
 public:
  NamedTemporaries() { ::setenv("COINROLL_NAMED_TEMPORARIES", "1", 1); }
  ~NamedTemporaries() { ::unsetenv("COINROLL_NAMED_TEMPORARIES"); }
  NamedTemporaries(const NamedTemporaries&) = delete;
  NamedTemporaries& operator=(const NamedTemporaries&) = delete;
};

}  // namespace coinroll::testing
