#pragma once
// A fresh, empty directory per test, named after the suite, the test and the process (two test
// runs on one machine, or two ctest jobs, must never share one), removed afterwards: where tests
// write their scenes and outputs.

#include <gtest/gtest.h>

#include <filesystem>
#include <iterator>
#include <optional>
#include <string>
#include <system_error>

#include <unistd.h>

namespace coinroll::testing {

class ScratchDirectory {
 public:
  ScratchDirectory() {
    const ::testing::TestInfo& test = *::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() / ("coinroll_" + std::string(test.test_suite_name()) + "_" +
                                                      std::string(test.name()) + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDirectory() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchDirectory(const ScratchDirectory&) = delete;
  ScratchDirectory& operator=(const ScratchDirectory&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }
  int fileCount() const {
    return static_cast<int>(
        std::distance(std::filesystem::directory_iterator(path_), std::filesystem::directory_iterator{}));
  }

 private:
  std::filesystem::path path_;
};

// The fixture form, for suites whose every test writes files: the directory is `dir_`.
class ScratchDirTest : public ::testing::Test {
 protected:
  void SetUp() override {
    scratch_.emplace();
    dir_ = scratch_->path();
  }
  void TearDown() override { scratch_.reset(); }

  std::optional<ScratchDirectory> scratch_;
  std::filesystem::path dir_;
};

}  // namespace coinroll::testing
