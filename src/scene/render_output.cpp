#include "scene/render_output.h"

#include <algorithm>

namespace coinroll::scene {

std::optional<PictureSize> pictureSizeNamed(std::string_view name) {
  const auto found =
      std::find_if(kPictureSizes.begin(), kPictureSizes.end(), [&](const PictureSize& s) { return s.name == name; });
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

}  // namespace coinroll::scene
