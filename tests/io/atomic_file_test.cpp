#include "io/atomic_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include <unistd.h>

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

TEST(AtomicOutputFile, ANameTheFileSystemCannotHoldIsRefusedBeforeAnyWork) {
  // Refused when the output is opened, not at the rename after all the frames or rows.
  const coinroll::testing::ScratchDirectory scratch;
  const long limit = ::pathconf(scratch.path().c_str(), _PC_NAME_MAX);
  ASSERT_GT(limit, 4);
  const std::string longest = std::string(static_cast<std::size_t>(limit) - 4, 'a') + ".csv";
  {
    AtomicOutputFile file(scratch / longest);
    std::ofstream(file.temporaryPath()) << "data\n";
    file.commit();
  }
  EXPECT_TRUE(fs::exists(scratch / longest));
  fs::remove(scratch / longest);
  try {
    AtomicOutputFile file(scratch / ("a" + longest));
    FAIL() << "a name of " << limit + 1 << " bytes was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("File name too long"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(fs::is_empty(scratch.path()));
}
