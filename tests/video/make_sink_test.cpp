#include "video/make_sink.h"

#include <gtest/gtest.h>

#include "synthetic_frames.h"
#include "video/png_sequence_sink.h"

using coinroll::video::makeSinkForPath;
using coinroll::video::VideoOptions;
using namespace coinroll::video::testing;

TEST(MakeSinkForPath, ChoosesBySuffixOrPattern) {
  ScratchDirectory directory;
  EXPECT_NE(dynamic_cast<coinroll::video::EncoderSink*>(makeSinkForPath(directory / "a.mp4", VideoOptions{}).get()),
            nullptr);
  EXPECT_NE(dynamic_cast<coinroll::video::EncoderSink*>(makeSinkForPath(directory / "A.MP4", VideoOptions{}).get()),
            nullptr);
  EXPECT_NE(
      dynamic_cast<coinroll::video::PngSequenceSink*>(makeSinkForPath(directory / "f_%04d.png", VideoOptions{}).get()),
      nullptr);
  EXPECT_EQ(directory.fileCount(), 0);
}

TEST(MakeSinkForPath, TheExtensionNamesTheVideoKindInAnyCase) {
  using coinroll::video::VideoFormat;
  using coinroll::video::videoFormatOf;
  EXPECT_EQ(videoFormatOf("a.mp4"), VideoFormat::Mp4);
  EXPECT_EQ(videoFormatOf("a.GIF"), VideoFormat::Gif);
  EXPECT_EQ(videoFormatOf("dir/a.WebM"), VideoFormat::WebM);
  EXPECT_EQ(videoFormatOf("a.Mov"), VideoFormat::Mov);
  EXPECT_EQ(videoFormatOf("100%d.gif"), VideoFormat::Gif);  // a video name: its % is a literal character
  EXPECT_EQ(videoFormatOf("/dev/null"), VideoFormat::Mp4);  // no extension to go by: the default kind
  EXPECT_EQ(videoFormatOf("f_%05d.png"), std::nullopt);
  EXPECT_EQ(videoFormatOf("a.avi"), std::nullopt);
  ScratchDirectory directory;
  for (const char* name : {"a.gif", "a.WEBM", "a.mov"}) {
    EXPECT_NE(dynamic_cast<coinroll::video::EncoderSink*>(makeSinkForPath(directory / name, VideoOptions{}).get()),
              nullptr)
        << name;
  }
  EXPECT_EQ(directory.fileCount(), 0);  // unfinished sinks leave nothing
}

TEST(MakeSinkForPath, AnEscapedPercentInAVideoNameIsNoPattern) {
  // "%%" is a literal percent sign, not a conversion: this is a video, not a PNG sequence.
  ScratchDirectory directory;
  EXPECT_NE(dynamic_cast<coinroll::video::EncoderSink*>(makeSinkForPath(directory / "100%%.mp4", VideoOptions{}).get()),
            nullptr);
  EXPECT_NE(dynamic_cast<coinroll::video::PngSequenceSink*>(
                makeSinkForPath(directory / "100%%_%d.png", VideoOptions{}).get()),
            nullptr);
}

TEST(MakeSinkForPath, UnknownKindNamesThePathAndBothForms) {
  ScratchDirectory directory;
  const std::filesystem::path path = directory / "clip.avi";
  try {
    makeSinkForPath(path, VideoOptions{});
    FAIL() << "accepted " << path;
  } catch (const std::invalid_argument& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    EXPECT_NE(message.find(".mp4"), std::string::npos) << message;
    EXPECT_NE(message.find("%05d"), std::string::npos) << message;
  }
}
