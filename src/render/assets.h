#pragma once
// Images the renderer draws with, from assets/: the copies embedded at build time, so a binary
// draws the same pixels wherever it runs; $COINROLL_ASSET_DIR, when set, names a directory to
// read them from instead.

#include <string_view>

#include "image/image.h"

namespace coinroll::render {

// Throws std::runtime_error naming the asset and where it looked if it cannot be read.
image::Image loadAssetImage(std::string_view name);

}  // namespace coinroll::render
