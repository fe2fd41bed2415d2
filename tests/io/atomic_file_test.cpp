#include "io/atomic_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace fs = std::filesystem;
using coinroll::io::AtomicOutputFile;

namespace {

fs::path freshDirectory(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("coinroll_io_test_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

}  // namespace

TEST(AtomicOutputFile, NothingAppearsUnderTheFinalNameUntilCommit) {
  const fs::path dir = freshDirectory("commit");
  const fs::path target = dir / "out.csv";
  {
    AtomicOutputFile file(target);
    std::ofstream(file.temporaryPath()) << "data\n";
    EXPECT_FALSE(fs::exists(target));
    file.commit();
  }
  ASSERT_TRUE(fs::exists(target));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1);
}

TEST(AtomicOutputFile, AbandonedFileLeavesNothingBehind) {
  const fs::path dir = freshDirectory("abandon");
  {
    AtomicOutputFile file(dir / "out.csv");
    std::ofstream(file.temporaryPath()) << "half";
  }
  EXPECT_TRUE(fs::is_empty(dir));
}

TEST(AtomicOutputFile, MissingDirectoryIsReportedWithThePath) {
  const fs::path target = fs::temp_directory_path() / "coinroll_no_such_dir" / "x" / "out.csv";
  try {
    AtomicOutputFile file(target);
    FAIL() << "expected an exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("out.csv"), std::string::npos) << e.what();
  }
}
