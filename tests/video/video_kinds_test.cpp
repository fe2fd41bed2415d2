// The table of video kinds (video/video_kinds.h): one row per kind, the output-name rule read from
// it, and the refusals of outputs that cannot carry what a render asks for, worded from it.

#include "video/video_kinds.h"

#include <gtest/gtest.h>

#include <set>
#include <stdexcept>
#include <string>

namespace coinroll::video {
namespace {

TEST(VideoKinds, EveryKindHasOneRowFoundByItsFormatAndAnExtensionOfItsOwn) {
  std::set<std::string_view> extensions;
  for (const VideoKind& kind : videoKinds()) {
    EXPECT_EQ(&videoKind(kind.format), &kind) << kind.label;
    EXPECT_EQ(kind.extension.front(), '.') << kind.label;
    EXPECT_TRUE(extensions.insert(kind.extension).second) << kind.extension << " names two kinds";
    EXPECT_NE(kind.extension, kPngExtension) << kind.label;
  }
}

TEST(OutputNames, AnExtensionIsRecognisedInAnyCaseAndOnlyAsTheWholeExtension) {
  EXPECT_TRUE(namesExtension("a.png", kPngExtension));
  EXPECT_TRUE(namesExtension("UP.PNG", kPngExtension));
  EXPECT_TRUE(namesExtension("dir.d/Still.Png", kPngExtension));
  EXPECT_TRUE(namesExtension("clip.GIF", ".gif"));
  EXPECT_FALSE(namesExtension("a.png.mp4", kPngExtension));
  EXPECT_FALSE(namesExtension("apng", kPngExtension));
  EXPECT_FALSE(namesExtension("a.pngx", kPngExtension));
  EXPECT_FALSE(namesExtension(".png", kPngExtension));  // a hidden file's name, no extension
  EXPECT_FALSE(namesExtension("a.", kPngExtension));
}

TEST(OutputNames, ListsReadAsEnglish) {
  EXPECT_EQ(joinedWithOr(std::vector<std::string>{"a"}), "a");
  EXPECT_EQ(joinedWithOr(std::vector<std::string>{"a", "b"}), "a or b");
  EXPECT_EQ(joinedWithOr(std::vector<std::string>{"a", "b", "c"}), "a, b or c");
}

std::string refusal(const VideoOptions& wanted, VideoFormat format) {
  try {
    refuseOutputThatCannotCarry(wanted, format);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "accepted";
}

TEST(OutputFormats, ATransparentBackgroundNeedsAKindWithAlpha) {
  VideoOptions transparent;
  transparent.alpha = true;
  EXPECT_EQ(
      refusal(transparent, VideoFormat::Mp4),
      "render.background: \"transparent\" needs an output with alpha, and .mp4 has none; write a .webm, a .mov or "
      "a PNG sequence (out_%05d.png), or set render.background to \"opaque\"");
  EXPECT_NE(refusal(transparent, VideoFormat::Gif).find("and .gif has none"), std::string::npos);
  EXPECT_EQ(refusal(transparent, VideoFormat::Mov), "accepted");
  EXPECT_EQ(refusal(transparent, VideoFormat::WebM), "accepted");
  EXPECT_EQ(refusal(VideoOptions{}, VideoFormat::Mp4), "accepted");
}

TEST(OutputFormats, ASoundTrackNeedsAKindThatHoldsAudio) {
  VideoOptions withSound;
  withSound.audio = true;
  EXPECT_EQ(refusal(withSound, VideoFormat::WebM),
            "render.audio: a .webm gets no sound track; write a .mp4 or a .mov, or leave the sound out with --set "
            "render.audio=null");
  EXPECT_EQ(refusal(withSound, VideoFormat::Gif),
            "render.audio: a .gif gets no sound track; write a .mp4 or a .mov, or leave the sound out with --set "
            "render.audio=null");
  EXPECT_EQ(refusal(withSound, VideoFormat::Mp4), "accepted");
  EXPECT_EQ(refusal(withSound, VideoFormat::Mov), "accepted");
}

TEST(OutputFormats, AGifPlaysAtMost50FpsAndTheRefusalSaysWhyAndWhatElseCarriesTheRate) {
  VideoOptions fast;
  fast.fps = 60;
  EXPECT_EQ(refusal(fast, VideoFormat::Gif),
            "render.fps: a .gif plays at most 50 fps (its frame delays are whole hundredths of a second, and browsers "
            "play a delay under 2 as 10), got 60; set render.fps to 50 or less, or write a .mp4, a .webm or a .mov");
  for (const VideoFormat format : {VideoFormat::Mp4, VideoFormat::WebM, VideoFormat::Mov}) {
    fast.fps = 240;
    EXPECT_EQ(refusal(fast, format), "accepted") << videoKind(format).label;
  }
  fast.fps = 50;
  EXPECT_EQ(refusal(fast, VideoFormat::Gif), "accepted");
}

}  // namespace
}  // namespace coinroll::video
