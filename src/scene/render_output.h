#pragma once
// What a render's command line asks of a scene's picture and output: a named picture size, and
// whether the output's video kind can carry what the scene's render block wants in it.

#include <array>
#include <optional>
#include <string>
#include <string_view>

#include "scene/scene_config.h"
#include "video/video_options.h"

namespace coinroll::scene {

// render --size's names: the usual video heights with 16:9 sides, even for 4:2:0 chroma (854 for 480p).
struct PictureSize {
  std::string_view name;
  int width = 0, height = 0;  // pixels: render.width, render.height
};
inline constexpr std::array<PictureSize, 5> kPictureSizes = {{
    {"480p", 854, 480}, {"720p", 1280, 720}, {"1080p", 1920, 1080}, {"1440p", 2560, 1440}, {"2160p", 3840, 2160}}};

std::optional<PictureSize> pictureSizeNamed(std::string_view name);
// "480p, 720p, 1080p, 1440p or 2160p" for messages.
std::string pictureSizeNames();

// Throws SceneError naming the render field and the kinds that carry it when `format` cannot hold
// what `render` asks for: a transparent background (render.background) in a kind without alpha,
// or a sound track (render.audio) in one without audio (video::keepsAlpha, video::holdsAudio).
void refuseOutputThatCannotCarry(const RenderSpec& render, video::VideoFormat format);

}  // namespace coinroll::scene
