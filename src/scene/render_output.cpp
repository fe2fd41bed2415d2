#include "scene/render_output.h"

#include <fmt/format.h>

#include <algorithm>

#include "scene/scene_error.h"

namespace coinroll::scene {

std::optional<PictureSize> pictureSizeNamed(std::string_view name) {
  const auto found = std::find_if(kPictureSizes.begin(), kPictureSizes.end(), [&](const PictureSize& s) { return s.name == name; });
  if (found == kPictureSizes.end()) return std::nullopt;
  return *found;
}

std::string pictureSizeNames() {
  std::string names;
  for (std::size_t i = 0; i < kPictureSizes.size(); ++i) {
    names += (i == 0 ? "" : i + 1 == kPictureSizes.size() ? " or " : ", ") + std::string(kPictureSizes[i].name);
  }
  return names;
}

void refuseOutputThatCannotCarry(const RenderSpec& render, video::VideoFormat format) {
  const std::string_view extension = video::extensionOf(format);
  if (render.picture.transparentBackground && !video::keepsAlpha(format)) {
    throw SceneError(fmt::format("render.background: \"transparent\" needs an output with alpha, and {} has none; write a "
                                 ".mov, a .webm or a PNG sequence (out_%05d.png), or set render.background to \"opaque\"",
                                 extension));
  }
  if (render.audio && !video::holdsAudio(format)) {
    throw SceneError(fmt::format("render.audio: a {} gets no sound track; write a .mp4 or a .mov, or remove render.audio",
                                 extension));
  }
}

}  // namespace coinroll::scene
