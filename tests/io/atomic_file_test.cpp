#include "io/atomic_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "scratch_dir.h"

namespace fs = std::filesystem;
using coinroll::io::AtomicOutputFile;


TEST(AtomicOutputFile, NothingAppearsUnderTheFinalNameUntilCommit) {
  const coinroll::testing::ScratchDirectory scratch;
  const fs::path& dir = scratch.path();
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
  const coinroll::testing::ScratchDirectory scratch;
  const fs::path& dir = scratch.path();
  {
    AtomicOutputFile file(dir / "out.csv");
    std::ofstream(file.temporaryPath()) << "half";
  }
  EXPECT_TRUE(fs::is_empty(dir));
}

TEST(AtomicOutputFile, MissingDirectoryIsReportedWithThePath) {
  const coinroll::testing::ScratchDirectory scratch;
  const fs::path target = scratch / "no_such_dir" / "x" / "out.csv";
  try {
    AtomicOutputFile file(target);
    FAIL() << "expected an exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("out.csv"), std::string::npos) << e.what();
  }
}
