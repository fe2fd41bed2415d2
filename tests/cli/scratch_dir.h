#pragma once
// A fresh, empty directory per test, named after the suite, the test and the process (two test
// runs on one machine must not share it), removed afterwards: what the command-line tests write
// their scenes and outputs into.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include <unistd.h>

namespace coinroll::testing {

class ScratchDirTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const ::testing::TestInfo& test = *::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           ("coinroll_" + std::string(test.test_suite_name()) + "_" + std::string(test.name()) + "_" +
            std::to_string(::getpid()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::filesystem::path dir_;
};

}  // namespace coinroll::testing
