#include "image/image.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "scratch_dir.h"

namespace fs = std::filesystem;
using coinroll::image::Image;

TEST(Png, RoundTripKeepsEveryByte) {
  Image original(7, 5);
  for (std::size_t i = 0; i < original.rgba.size(); ++i) original.rgba[i] = static_cast<std::uint8_t>(i * 37 + 11);
  const coinroll::testing::ScratchDirectory scratch;
  const fs::path path = scratch / "roundtrip.png";
  coinroll::image::writePng(original, path);
  const Image read = coinroll::image::readPng(path);
  EXPECT_EQ(read.width, 7);
  EXPECT_EQ(read.height, 5);
  EXPECT_EQ(read.rgba, original.rgba);
}

TEST(Png, InconsistentImageIsRefusedAndNothingWritten) {
  Image broken(4, 4);
  broken.rgba.resize(3);
  const coinroll::testing::ScratchDirectory scratch;
  const fs::path path = scratch / "broken.png";
  EXPECT_THROW(coinroll::image::writePng(broken, path), std::runtime_error);
  EXPECT_FALSE(fs::exists(path));
}

TEST(Png, TextChunksFollowTheHeaderWithValidCrcsAndLeaveThePixels) {
  Image original(6, 3);
  for (std::size_t i = 0; i < original.rgba.size(); ++i) original.rgba[i] = static_cast<std::uint8_t>(i * 13 + 5);
  const coinroll::testing::ScratchDirectory scratch;
  const fs::path path = scratch / "text.png";
  coinroll::image::writePng(original, path, {{"Software", "coinroll 0.1.0"}, {"Comment", "scene fnv1a64:00ff"}});
  std::ifstream file(path, std::ios::binary);
  const std::string bytes{std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
  // Signature (8), IHDR (25), then the first tEXt chunk: length 23 = "Software" NUL "coinroll 0.1.0".
  EXPECT_EQ(bytes.substr(33, 8), std::string("\0\0\0\x17tEXt", 8));
  EXPECT_EQ(bytes.substr(41, 23), std::string("Software\0coinroll 0.1.0", 23));
  EXPECT_NE(bytes.find(std::string("tEXtComment\0scene fnv1a64:00ff", 30)), std::string::npos);
  EXPECT_NO_THROW(coinroll::image::checkPngChunks(path));  // every CRC right
  EXPECT_EQ(coinroll::image::readPng(path).rgba, original.rgba);
}

TEST(Png, ABadTextKeyIsRefusedAndNothingWritten) {
  const coinroll::testing::ScratchDirectory scratch;
  const fs::path path = scratch / "badkey.png";
  EXPECT_THROW(coinroll::image::writePng(Image(2, 2), path, {{"", "no key"}}), std::invalid_argument);
  EXPECT_FALSE(fs::exists(path));
}
