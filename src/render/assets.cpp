#include "render/assets.h"

#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <stdexcept>

#include "render/embedded_assets.h"

namespace coinroll::render {

image::Image loadAssetImage(std::string_view name) {
  if (const char* dir = std::getenv("COINROLL_ASSET_DIR"); dir != nullptr && *dir != '\0') {
    // An override a user may have forgotten: the message says where the path came from and how to
    // go back to the built-in file.
    try {
      return image::readPng(std::filesystem::path(dir) / name);
    } catch (const std::runtime_error& e) {
      throw std::runtime_error(
          fmt::format("{} ($COINROLL_ASSET_DIR names the directory it is read from; put a PNG {} "
                      "there, or unset it for the built-in one)",
                      e.what(), name));
    }
  }
  const std::optional<std::span<const std::uint8_t>> embedded = embeddedAsset(name);
  if (!embedded) throw std::runtime_error(fmt::format("asset: no asset named {}", name));
  return image::decodePng(*embedded, fmt::format("embedded:{}", name));
}

}  // namespace coinroll::render
