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
    return image::readPng(std::filesystem::path(dir) / name);
  }
  const std::optional<std::span<const std::uint8_t>> embedded = embeddedAsset(name);
  if (!embedded) throw std::runtime_error(fmt::format("asset: no asset named {}", name));
  return image::decodePng(*embedded, fmt::format("embedded:{}", name));
}

}  // namespace coinroll::render
