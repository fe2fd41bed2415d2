// io::RuntimeLibrary, through which coinroll reaches FFmpeg and Mesa only when it renders: a
// symbol resolves to the library's own function, and a missing library or symbol is an error
// naming it and what to install.

#include <gtest/gtest.h>
#include <zlib.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "io/runtime_library.h"
#include "scratch_dir.h"

namespace {

using coinroll::io::RuntimeLibrary;

std::string messageOf(RuntimeLibrary& library, const char* symbol) {
  try {
    library.symbol(symbol);
  } catch (const std::runtime_error& error) {
    return error.what();
  }
  return "";
}

TEST(RuntimeLibrary, ASymbolIsTheLibrarysOwnFunction) {
  // zlib is linked into this test, so the address dlopen finds must be the one the linker bound.
  RuntimeLibrary zlib("libz.so.1", "zlib1g");
  EXPECT_EQ(zlib.symbol("zlibVersion"), reinterpret_cast<void*>(&zlibVersion));
  EXPECT_EQ(zlib.symbol("crc32"), reinterpret_cast<void*>(&crc32));
}

TEST(RuntimeLibrary, AMissingLibraryNamesItAndItsPackage) {
  RuntimeLibrary missing("libcoinroll-no-such-library.so.7", "libcoinroll-no-such7");
  const std::string message = messageOf(missing, "anything");
  EXPECT_NE(message.find("cannot load libcoinroll-no-such-library.so.7"), std::string::npos) << message;
  EXPECT_NE(message.find("install libcoinroll-no-such7"), std::string::npos) << message;
}

TEST(RuntimeLibrary, AMissingFunctionNamesItAndTheLibrary) {
  RuntimeLibrary zlib("libz.so.1", "zlib1g");
  const std::string message = messageOf(zlib, "coinroll_no_such_function");
  EXPECT_NE(message.find("libz.so.1 has no function coinroll_no_such_function"), std::string::npos) << message;
}

// A broken libavcodec.so.59 was once reported as "cannot load libavformat.so.59 (...): install
// libavformat59", the package that is fine. Here a library (the fixture libraries of tests/
// CMakeLists.txt) whose needed library beside it is broken: the message names the needed one as what
// to repair, and the intact pair loads.
TEST(RuntimeLibrary, ABrokenLibraryItNeedsIsNamedAsWhatToRepair) {
  namespace fs = std::filesystem;
  const coinroll::testing::ScratchDirectory dir;
  const fs::path brokenDir = dir.path() / "broken", intactDir = dir.path() / "intact";
  fs::create_directories(brokenDir);
  fs::create_directories(intactDir);
  const fs::path needing = brokenDir / fs::path(COINROLL_FIXTURE_NEEDING).filename();
  const fs::path needed = brokenDir / fs::path(COINROLL_FIXTURE_NEEDED).filename();
  fs::copy_file(COINROLL_FIXTURE_NEEDING, needing);
  std::ofstream(needed) << "not a shared library\n";
  RuntimeLibrary broken(needing.string(), "coinroll-fixture");
  const std::string message = messageOf(broken, "coinroll_fixture_needing");
  const std::string neededName = needed.filename().string();
  EXPECT_NE(message.find("a library it needs, " + neededName + ", cannot be loaded"), std::string::npos) << message;
  EXPECT_NE(message.find("reinstall the package that provides " + neededName), std::string::npos) << message;

  fs::copy_file(COINROLL_FIXTURE_NEEDING, intactDir / needing.filename());
  fs::copy_file(COINROLL_FIXTURE_NEEDED, intactDir / needed.filename());
  RuntimeLibrary loads((intactDir / needing.filename()).string(), "coinroll-fixture");
  const auto function = reinterpret_cast<int (*)()>(loads.symbol("coinroll_fixture_needing"));
  EXPECT_EQ(function(), 8);
}

}  // namespace
