// io::RuntimeLibrary, through which coinroll reaches FFmpeg and Mesa only when it renders: a
// symbol resolves to the library's own function, and a missing library or symbol is an error
// naming it and what to install.

#include <gtest/gtest.h>
#include <zlib.h>

#include <stdexcept>
#include <string>

#include "io/runtime_library.h"

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

}  // namespace
