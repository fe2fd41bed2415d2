#pragma once
// render --size's named picture sizes. Whether an output can carry what a render block asks for
// is the output kinds' own to say (video/video_kinds.h).

#include <array>
#include <optional>
#include <string>
#include <string_view>

namespace coinroll::scene {

// render --size's names: the usual video heights with 16:9 sides, even for 4:2:0 chroma (854 for 480p).
struct PictureSize {
  std::string_view name;
  int width = 0, height = 0;  // pixels: render.width, render.height
};
inline constexpr std::array<PictureSize, 5> kPictureSizes = {
    {{"480p", 854, 480}, {"720p", 1280, 720}, {"1080p", 1920, 1080}, {"1440p", 2560, 1440}, {"2160p", 3840, 2160}}};

std::optional<PictureSize> pictureSizeNamed(std::string_view name);
// "480p, 720p, 1080p, 1440p or 2160p" for messages.
std::string pictureSizeNames();

}  // namespace coinroll::scene
