// render --size's presets, as scene/render_output.h gives them to the command line; the
// anti-aliasing each output draws with (RenderSpec::pictureFor).

#include "scene/render_output.h"

#include <gtest/gtest.h>

#include <string>

#include "render/render_settings.h"
#include "scene/scene_loader.h"

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

SceneConfig defaultSceneWith(const std::vector<std::string>& overrides) {
  nlohmann::json document = builtInDefaultScene();
  for (const std::string& override : overrides) applyOverride(document, override);
  return parseScene(document, "test");
}

// docs/quality.md "Anti-aliasing": a still takes 2x2 SSAA with 4x MSAA, a video from a fixed camera
// 2x2 SSAA with one sample, one from a moving camera 4x MSAA; what a scene names is kept as named.
TEST(PictureAntialiasing, AutoChoosesPerOutputAndANamedMethodStays) {
  using render::Antialiasing;
  const SceneConfig scene = defaultSceneWith({});
  EXPECT_EQ(scene.render.picture.antialiasing, Antialiasing::Auto);
  const render::RenderSettings still = scene.render.pictureFor(RenderSpec::Output::Still);
  EXPECT_EQ(still.antialiasing, Antialiasing::Ssaa);
  EXPECT_EQ(still.msaa, 4);
  const render::RenderSettings video = scene.render.pictureFor(RenderSpec::Output::Video);
  EXPECT_EQ(video.antialiasing, Antialiasing::Ssaa);
  EXPECT_EQ(video.msaa, 1);
  const render::RenderSettings orbit =
      defaultSceneWith({"render.camera.mode=orbit"}).render.pictureFor(RenderSpec::Output::Video);
  EXPECT_EQ(orbit.antialiasing, Antialiasing::Msaa);
  EXPECT_EQ(orbit.msaa, 4);
  // Doubled, a picture wider than 3840 would pass the 7680-pixel side: its buffers would take gigabytes.
  const render::RenderSettings wide =
      defaultSceneWith({"render.width=3842"}).render.pictureFor(RenderSpec::Output::Still);
  EXPECT_EQ(wide.antialiasing, Antialiasing::Msaa);
  const render::RenderSettings widest =
      defaultSceneWith({"render.width=3840"}).render.pictureFor(RenderSpec::Output::Still);
  EXPECT_EQ(widest.antialiasing, Antialiasing::Ssaa);
  for (const auto& [name, method] :
       {std::pair{"msaa", Antialiasing::Msaa}, {"fxaa", Antialiasing::Fxaa}, {"ssaa", Antialiasing::Ssaa}}) {
    const SceneConfig named = defaultSceneWith({std::string("render.antialiasing=") + name, "render.msaa=2"});
    for (const auto output : {RenderSpec::Output::Still, RenderSpec::Output::Video}) {
      EXPECT_EQ(named.render.pictureFor(output).antialiasing, method) << name;
      EXPECT_EQ(named.render.pictureFor(output).msaa, 2) << name;
    }
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
