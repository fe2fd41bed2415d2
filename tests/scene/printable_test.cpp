// How messages quote what users gave: control characters shown, never sent to the terminal.

#include "scene/json_reader.h"

#include <gtest/gtest.h>

#include <string>

namespace coinroll::scene {
namespace {

TEST(Printable, ControlCharactersAreShownAsEscapesAndLineBreaksAsBackslashN) {
  EXPECT_EQ(printable("a\nb.json"), "a\\nb.json");
  EXPECT_EQ(printable("\x1b[31mred.png"), "\\x1b[31mred.png");
  EXPECT_EQ(printable(std::string("a\0b", 3)), "a\\x00b");
  EXPECT_EQ(printable("tab\there\x7f"), "tab\there\\x7f");                   // a tab is kept, DEL is not
  EXPECT_EQ(printable("caf\xc3\xa9 scene.json"), "caf\xc3\xa9 scene.json");  // UTF-8 passes as it is
}

TEST(Printable, AKeyWithControlCharactersIsShownAsAJsonString) {
  EXPECT_EQ(printableKey("theta"), "theta");
  EXPECT_EQ(printableKey(std::string("ab\0c\x1b[31m", 9)), "\"ab\\u0000c\\u001b[31m\"");
  EXPECT_EQ(printableKey("a\tb"), "\"a\\tb\"");  // in a key even a tab is escaped: keys are JSON strings
}

}  // namespace
}  // namespace coinroll::scene
