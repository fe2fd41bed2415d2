#pragma once
// The files of assets/, compiled into the binary by cmake/embed_assets.cmake.

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

namespace coinroll::render {

std::optional<std::span<const std::uint8_t>> embeddedAsset(std::string_view name);

}  // namespace coinroll::render
