#pragma once
// Outputs are written under a temporary name beside the destination and renamed onto it only
// when complete, so a failed or interrupted run never leaves a truncated file under the final
// name (rename(2) within one directory is atomic on POSIX file systems).

#include <filesystem>
#include <string>

namespace coinroll::io {

class AtomicOutputFile {
 public:
  // Reserves a temporary path beside `destination`. Throws std::runtime_error naming the
  // destination if its directory does not exist or is not writable.
  explicit AtomicOutputFile(std::filesystem::path destination);
  ~AtomicOutputFile();  // removes the temporary file unless commit() succeeded

  AtomicOutputFile(const AtomicOutputFile&) = delete;
  AtomicOutputFile& operator=(const AtomicOutputFile&) = delete;

  // Where to write the content (a unique name in the destination's directory).
  const std::filesystem::path& temporaryPath() const { return temporary_; }
  const std::filesystem::path& destination() const { return destination_; }

  // Renames the temporary file onto the destination. Throws if the rename fails.
  void commit();

 private:
  std::filesystem::path destination_;
  std::filesystem::path temporary_;
  bool committed_ = false;
};

}  // namespace coinroll::io
