#include "image/image.h"

#include <gtest/gtest.h>

#include <filesystem>

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
