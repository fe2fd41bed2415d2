#include "video/png_sequence_sink.h"

#include <gtest/gtest.h>

#include "synthetic_frames.h"

namespace fs = std::filesystem;
using coinroll::video::PngSequenceSink;
using namespace coinroll::video::testing;

TEST(PngSequenceSink, WritesNumberedFilesFromZeroWithTheFramesPixels) {
  ScratchDirectory directory;
  constexpr int kFrames = 3;
  {
    PngSequenceSink sink(directory / "frame_%05d.png");
    for (int i = 0; i < kFrames; ++i) sink.push(movingSquareFrame(32, 18, i));
    sink.finish();
  }
  EXPECT_EQ(directory.fileCount(), kFrames);
  for (int i = 0; i < kFrames; ++i) {
    const fs::path path = directory / ("frame_0000" + std::to_string(i) + ".png");
    ASSERT_TRUE(fs::exists(path)) << path;
    EXPECT_EQ(coinroll::image::readPng(path).rgba, movingSquareFrame(32, 18, i).rgba) << path;
  }
}

TEST(PngSequenceSink, PlainPercentDAndEscapedPercentAreHonoured) {
  ScratchDirectory directory;
  PngSequenceSink sink(directory / "100%%_%d.png");
  EXPECT_EQ(sink.pathOfFrame(12), directory / "100%_12.png");
}

TEST(PngSequenceSink, ZeroPaddingWidthsOneToTenAreHonoured) {
  // The pattern's contract: %0Nd with N = 1..10 pads the frame number with zeros to N digits.
  ScratchDirectory directory;
  for (int width = 1; width <= 10; ++width) {
    const std::string conversion = "%0" + std::to_string(width) + "d";
    PngSequenceSink sink(directory / ("f_" + conversion + ".png"));
    const std::string number = std::to_string(42);
    const std::string padded = std::string(width > 2 ? width - 2 : 0, '0') + number;
    EXPECT_EQ(sink.pathOfFrame(42), directory / ("f_" + padded + ".png")) << conversion;
  }
}

TEST(PngSequenceSink, OnlyAnUnescapedPercentMakesASequencePattern) {
  // "%%" is a literal percent sign: names holding only escapes are plain files.
  using coinroll::video::looksLikeSequencePattern;
  EXPECT_TRUE(looksLikeSequencePattern("frame_%05d.png"));
  EXPECT_TRUE(looksLikeSequencePattern("100%%_%d.png"));
  EXPECT_TRUE(looksLikeSequencePattern("%%%d.png"));
  EXPECT_FALSE(looksLikeSequencePattern("100%%.mp4"));
  EXPECT_FALSE(looksLikeSequencePattern("a%%b%%c.png"));
  EXPECT_FALSE(looksLikeSequencePattern("%%"));
  EXPECT_FALSE(looksLikeSequencePattern("clip.mp4"));
}

TEST(PngSequenceSink, PercentInTheDirectoryIsLiteral) {
  ScratchDirectory directory;
  fs::create_directory(directory / "50%d");
  PngSequenceSink sink(directory / "50%d" / "f_%03d.png");
  EXPECT_EQ(sink.pathOfFrame(7), directory / "50%d" / "f_007.png");
}

TEST(PngSequenceSink, DestroyedWithoutFinishRemovesItsFrames) {
  ScratchDirectory directory;
  {
    PngSequenceSink sink(directory / "frame_%03d.png");
    for (int i = 0; i < 4; ++i) sink.push(movingSquareFrame(32, 18, i));
  }
  EXPECT_EQ(directory.fileCount(), 0);
}

TEST(PngSequenceSink, EarlierFilesOfTheSameNamesSurviveAnUnfinishedRunAndAreReplacedByAFinishedOne) {
  ScratchDirectory directory;
  const fs::path earlier = directory / "frame_001.png";
  coinroll::image::writePng(movingSquareFrame(32, 18, 9), earlier);
  const auto earlierPixels = coinroll::image::readPng(earlier).rgba;
  {
    PngSequenceSink sink(directory / "frame_%03d.png");
    for (int i = 0; i < 3; ++i) sink.push(movingSquareFrame(32, 18, i));
  }  // interrupted: the user's file is untouched, nothing of ours remains
  EXPECT_EQ(directory.fileCount(), 1);
  EXPECT_EQ(coinroll::image::readPng(earlier).rgba, earlierPixels);
  {
    PngSequenceSink sink(directory / "frame_%03d.png");
    for (int i = 0; i < 3; ++i) sink.push(movingSquareFrame(32, 18, i));
    EXPECT_EQ(coinroll::image::readPng(earlier).rgba, earlierPixels);  // not before the run completes
    sink.finish();
  }
  EXPECT_EQ(directory.fileCount(), 3);
  EXPECT_EQ(coinroll::image::readPng(earlier).rgba, movingSquareFrame(32, 18, 1).rgba);
}

TEST(PngSequenceSink, MalformedPatternsAreRefusedNamingThePattern) {
  ScratchDirectory directory;
  for (const char* pattern : {"frame.png", "a_%d_%d.png", "frame_%s.png", "frame_%5d.png", "frame_%05d.jpg",
                              "frame_%0d.png", "frame_%d", "frame_%00d.png", "frame_%011d.png", "frame_%099d.png"}) {
    const fs::path path = directory / pattern;
    try {
      PngSequenceSink sink(path);
      ADD_FAILURE() << "accepted " << pattern;
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(std::string(error.what()).find(path.string()), std::string::npos) << error.what();
    }
  }
}

TEST(PngSequenceSink, MissingDirectoryIsReportedByPath) {
  ScratchDirectory directory;
  const fs::path pattern = directory / "missing" / "frame_%05d.png";
  EXPECT_THROW(PngSequenceSink sink(pattern), std::runtime_error);
}

// The pattern grammar on its own, as the sink and `coinroll render`'s check against its inputs
// read it: frame i's name, and which names are frames (only the exact name of a number).
TEST(SequencePattern, NamesFramesAndKnowsItsOwnNamesExactly) {
  using coinroll::video::parseSequencePattern;
  const coinroll::video::SequencePattern padded = parseSequencePattern("out/f_%03d.PNG");
  EXPECT_EQ(padded.prefix, "f_");
  EXPECT_EQ(padded.suffix, ".PNG");
  EXPECT_EQ(padded.minimumDigits, 3);
  EXPECT_EQ(padded.fileNameOf(7), "f_007.PNG");
  EXPECT_EQ(padded.fileNameOf(12345), "f_12345.PNG");
  EXPECT_EQ(padded.frameNumberOf("f_007.PNG"), 7);
  EXPECT_EQ(padded.frameNumberOf("f_12345.PNG"), 12345);
  EXPECT_EQ(padded.frameNumberOf("f_0007.PNG"), std::nullopt);  // no number gives four digits with a leading 0
  EXPECT_EQ(padded.frameNumberOf("f_07.PNG"), std::nullopt);
  EXPECT_EQ(padded.frameNumberOf("f_007.png"), std::nullopt);  // another suffix
  EXPECT_EQ(padded.frameNumberOf("f_.PNG"), std::nullopt);
  EXPECT_EQ(padded.frameNumberOf("f_99999999999.PNG"), std::nullopt);  // past any frame number
  const coinroll::video::SequencePattern plain = parseSequencePattern("100%%_%d.png");
  EXPECT_EQ(plain.prefix, "100%_");
  EXPECT_EQ(plain.minimumDigits, 0);
  EXPECT_EQ(plain.fileNameOf(0), "100%_0.png");
  EXPECT_EQ(plain.frameNumberOf("100%_42.png"), 42);
  EXPECT_EQ(plain.frameNumberOf("100%_042.png"), std::nullopt);
  EXPECT_THROW(parseSequencePattern("f_%s.png"), std::invalid_argument);
  EXPECT_THROW(parseSequencePattern("f_%d_%d.png"), std::invalid_argument);
  EXPECT_THROW(parseSequencePattern("f_%d.jpg"), std::invalid_argument);
}
