// render --size's presets and the refusal of outputs that cannot carry what a scene's render
// block asks for, as scene/render_output.h gives them to the command line.

#include "scene/render_output.h"

#include <gtest/gtest.h>

#include <string>

#include "render/render_settings.h"
#include "scene/scene_error.h"

namespace coinroll::scene {
namespace {

TEST(PictureSizes, EveryPresetIsA16By9PictureTheLoaderAccepts) {
  for (const PictureSize& size : kPictureSizes) {
    EXPECT_EQ(size.width % 2, 0) << size.name;  // 4:2:0 chroma halves both sides
    EXPECT_EQ(size.height % 2, 0) << size.name;
    EXPECT_GE(size.width, render::kMinImageSide) << size.name;
    EXPECT_LE(size.width, render::kMaxImageSide) << size.name;
    EXPECT_NEAR(static_cast<double>(size.width) / size.height, 16.0 / 9.0, 0.005) << size.name;
    EXPECT_EQ(std::to_string(size.height) + "p", size.name);
  }
}

TEST(PictureSizes, FoundByNameAndListedForMessages) {
  const std::optional<PictureSize> hd = pictureSizeNamed("1080p");
  ASSERT_TRUE(hd);
  EXPECT_EQ(hd->width, 1920);
  EXPECT_EQ(hd->height, 1080);
  EXPECT_EQ(pictureSizeNamed("480p")->width, 854);
  EXPECT_FALSE(pictureSizeNamed("4k"));
  EXPECT_FALSE(pictureSizeNamed("1080"));
  EXPECT_EQ(pictureSizeNames(), "480p, 720p, 1080p, 1440p or 2160p");
}

std::string refusal(const RenderSpec& render, video::VideoFormat format) {
  try {
    refuseOutputThatCannotCarry(render, format);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(OutputFormats, ATransparentBackgroundNeedsAKindWithAlpha) {
  RenderSpec transparent;
  transparent.picture.transparentBackground = true;
  EXPECT_EQ(refusal(transparent, video::VideoFormat::Mp4),
            "render.background: \"transparent\" needs an output with alpha, and .mp4 has none; write a .mov, a .webm or "
            "a PNG sequence (out_%05d.png), or set render.background to \"opaque\"");
  EXPECT_NE(refusal(transparent, video::VideoFormat::Gif).find("and .gif has none"), std::string::npos);
  EXPECT_EQ(refusal(transparent, video::VideoFormat::Mov), "accepted");
  EXPECT_EQ(refusal(transparent, video::VideoFormat::WebM), "accepted");
  EXPECT_EQ(refusal(RenderSpec{}, video::VideoFormat::Mp4), "accepted");
}

TEST(OutputFormats, ASoundTrackNeedsAKindThatHoldsAudio) {
  RenderSpec withSound;
  withSound.audio = AudioSpec{};
  EXPECT_EQ(refusal(withSound, video::VideoFormat::WebM),
            "render.audio: a .webm gets no sound track; write a .mp4 or a .mov, or remove render.audio");
  EXPECT_EQ(refusal(withSound, video::VideoFormat::Gif),
            "render.audio: a .gif gets no sound track; write a .mp4 or a .mov, or remove render.audio");
  EXPECT_EQ(refusal(withSound, video::VideoFormat::Mp4), "accepted");
  EXPECT_EQ(refusal(withSound, video::VideoFormat::Mov), "accepted");
}

}  // namespace
}  // namespace coinroll::scene
