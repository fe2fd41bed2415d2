// render --size's presets, as scene/render_output.h gives them to the command line.

#include "scene/render_output.h"

#include <gtest/gtest.h>

#include <string>

#include "render/render_settings.h"

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

}  // namespace
}  // namespace coinroll::scene
